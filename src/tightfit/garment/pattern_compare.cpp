#include "tightfit/garment/pattern_compare.hpp"

#include <string>

#include "tightfit/common/error.hpp"

namespace tightfit {
namespace {

std::string at(const std::string& path, size_t i) { return path + "/" + std::to_string(i); }

}  // namespace

bool same_pattern_meshes(const Pattern& a, const Pattern& b) {
  if (a.pieces.size() != b.pieces.size() || a.seams.size() != b.seams.size() ||
      a.pinned.size() != b.pinned.size())
    return false;
  for (size_t k = 0; k < a.pieces.size(); ++k) {
    const PatternPiece& p = a.pieces[k];
    const PatternPiece& q = b.pieces[k];
    if (p.name != q.name || p.rest.rows() != q.rest.rows() || p.triangles != q.triangles ||
        p.boundary != q.boundary || p.holes != q.holes || p.corners != q.corners)
      return false;
  }
  for (size_t s = 0; s < a.seams.size(); ++s) {
    const Seam& x = a.seams[s];
    const Seam& y = b.seams[s];
    if (x.name != y.name || x.a.piece != y.a.piece || x.a.vertices != y.a.vertices ||
        x.b.piece != y.b.piece || x.b.vertices != y.b.vertices)
      return false;
  }
  for (size_t s = 0; s < a.pinned.size(); ++s)
    if (a.pinned[s].name != b.pinned[s].name || a.pinned[s].piece != b.pinned[s].piece ||
        a.pinned[s].vertices != b.pinned[s].vertices)
      return false;
  return true;
}

void check_saved_pattern(const Pattern& saved, const Pattern& scene, const std::string& source,
                         const std::string& path, const std::string& hint) {
  auto fail = [&](const std::string& where, const std::string& what) {
    std::string message = path;
    message += "/";
    message += where;
    message += ": ";
    message += what;
    message += hint;
    throw InputError(source, message);
  };
  auto count = [&](const std::string& what, size_t n, size_t m) {
    if (n != m)
      fail(what, std::to_string(n) + " " + what + ", the scene's pattern has " + std::to_string(m));
  };
  auto same = [&](const std::string& where, const std::string& a, const std::string& b) {
    if (a != b) fail(where, "\"" + a + "\", the scene's is \"" + b + "\"");
  };
  auto same_piece = [&](const std::string& where, int a, int b) {
    if (a != b)
      fail(where, "piece " + std::to_string(a) + ", the scene's is piece " + std::to_string(b));
  };
  count("pieces", saved.pieces.size(), scene.pieces.size());
  for (size_t k = 0; k < scene.pieces.size(); ++k)
    same(at("pieces", k) + "/name", saved.pieces[k].name, scene.pieces[k].name);
  count("seams", saved.seams.size(), scene.seams.size());
  for (size_t k = 0; k < scene.seams.size(); ++k) {
    const std::string seam = at("seams", k);
    same(seam + "/name", saved.seams[k].name, scene.seams[k].name);
    same_piece(seam + "/a/piece", saved.seams[k].a.piece, scene.seams[k].a.piece);
    same_piece(seam + "/b/piece", saved.seams[k].b.piece, scene.seams[k].b.piece);
  }
  count("pinned", saved.pinned.size(), scene.pinned.size());
  for (size_t k = 0; k < scene.pinned.size(); ++k) {
    const std::string pin = at("pinned", k);
    same(pin + "/name", saved.pinned[k].name, scene.pinned[k].name);
    same_piece(pin + "/piece", saved.pinned[k].piece, scene.pinned[k].piece);
  }
}

}  // namespace tightfit
