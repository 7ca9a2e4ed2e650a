#include "tightfit/body/bvh.hpp"

#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <unordered_set>
#include <utility>

#include "tightfit/common/error.hpp"
#include "tightfit/geometry/text_parsing.hpp"

namespace tightfit {
namespace {

/// Most blocks (ROOT, JOINT, End Site) open at once.
constexpr std::size_t kBvhMaxDepth = 1000;
/// Most channels per joint (three positions, three rotations).
constexpr std::int64_t kBvhMaxJointChannels = 6;

/// A whitespace-separated token and the (1-based) line it is on.
struct BvhToken {
  std::string_view text;
  int line = 0;
};

bool bvh_is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

/// The tokens of a text, one at a time, with their line numbers. Cheap to copy (a copy
/// looks ahead without consuming).
class BvhTokens {
 public:
  explicit BvhTokens(std::string_view text) : text_(text) {}

  /// The next token, or nullopt at the end of the text.
  std::optional<BvhToken> next() {
    skip_blanks();
    if (pos_ >= text_.size()) return std::nullopt;
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !bvh_is_blank(text_[pos_])) ++pos_;
    last_line_ = line_;
    return BvhToken{text_.substr(start, pos_ - start), line_};
  }

  /// The next token without consuming it.
  std::optional<BvhToken> peek() const {
    BvhTokens ahead = *this;
    return ahead.next();
  }

  /// The following tokens that are on line `line` (consumed).
  std::vector<BvhToken> rest_of_line(int line) {
    std::vector<BvhToken> out;
    for (auto t = peek(); t && t->line == line; t = peek()) out.push_back(*next());
    return out;
  }

  /// How many tokens are left (none consumed).
  std::int64_t count_remaining() const {
    BvhTokens ahead = *this;
    std::int64_t n = 0;
    while (ahead.next()) ++n;
    return n;
  }

  /// Line of the token returned last (1 before the first), for end-of-file messages.
  int last_line() const { return last_line_; }
  /// Bytes after the token returned last.
  std::size_t remaining_bytes() const { return text_.size() - pos_; }

 private:
  void skip_blanks() {
    while (pos_ < text_.size() && bvh_is_blank(text_[pos_])) {
      if (text_[pos_] == '\n') ++line_;
      ++pos_;
    }
  }

  std::string_view text_;
  std::size_t pos_ = 0;
  int line_ = 1;
  int last_line_ = 1;
};

/// `token` in quotes for a message: at most 40 characters, unprintable bytes as '?'.
std::string bvh_quote(std::string_view token) {
  constexpr std::size_t kShown = 40;
  std::string out = "\"";
  for (const char c : token.substr(0, kShown))
    out += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
  if (token.size() > kShown) out += "...";
  return out + "\"";
}

bool bvh_equal_ignoring_case(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(a[i])) !=
        std::tolower(static_cast<unsigned char>(b[i])))
      return false;
  return true;
}

/// `token` as a finite number, nullopt if it is not a number or not finite.
std::optional<double> bvh_finite(std::string_view token) {
  const auto value = text::to_double(token);
  if (!value || !std::isfinite(*value)) return std::nullopt;
  return value;
}

/// The channel called `name` (any letter case), nullopt for an unknown name.
std::optional<BvhChannel> bvh_channel(std::string_view name) {
  static constexpr std::array<std::pair<std::string_view, BvhChannel>, 6> kNames{{
      {"Xposition", BvhChannel::kXposition},
      {"Yposition", BvhChannel::kYposition},
      {"Zposition", BvhChannel::kZposition},
      {"Xrotation", BvhChannel::kXrotation},
      {"Yrotation", BvhChannel::kYrotation},
      {"Zrotation", BvhChannel::kZrotation},
  }};
  for (const auto& [text, channel] : kNames)
    if (bvh_equal_ignoring_case(name, text)) return channel;
  return std::nullopt;
}

/// The rotation by `degrees` about axis 0 (x), 1 (y) or 2 (z), right-handed.
Mat3 bvh_axis_rotation(int axis, double degrees) {
  const double radians = degrees * std::numbers::pi / 180.0;
  const double c = std::cos(radians);
  const double s = std::sin(radians);
  Mat3 r;
  if (axis == 0)
    r << 1, 0, 0, 0, c, -s, 0, s, c;
  else if (axis == 1)
    r << c, 0, s, 0, 1, 0, -s, 0, c;
  else
    r << c, -s, 0, s, c, 0, 0, 0, 1;
  return r;
}

/// The rotation axis (0, 1, 2) of a rotation channel, -1 for a position channel.
int bvh_rotation_axis(BvhChannel channel) {
  switch (channel) {
    case BvhChannel::kXrotation:
      return 0;
    case BvhChannel::kYrotation:
      return 1;
    case BvhChannel::kZrotation:
      return 2;
    default:
      return -1;
  }
}

/// Parses one BVH text: the hierarchy with an explicit stack of open blocks, then the
/// motion.
class BvhParser {
 public:
  BvhParser(std::string_view text, const std::string& source) : tokens_(text) {
    motion_.source = source;
  }

  BvhMotion parse() {
    parse_hierarchy();
    parse_motion();
    return std::move(motion_);
  }

 private:
  /// An open ROOT, JOINT or End Site block.
  struct Block {
    int joint = -1;  ///< the joint, or the joint that owns the End Site
    bool end_site = false;
    int line = 0;  ///< where it opened
    bool has_offset = false;
    bool has_channels = false;
    bool has_children = false;
  };

  [[noreturn]] void fail(int line, const std::string& what) const {
    throw InputError(motion_.source, text::at_line(line) + what);
  }

  std::string block_name(const Block& block) const {
    const std::string joint = bvh_quote(motion_.joints[static_cast<std::size_t>(block.joint)].name);
    return block.end_site ? "the End Site of joint " + joint : "joint " + joint;
  }

  /// The next token; at the end of the text an error saying `expected` was expected.
  BvhToken next_or_fail(const std::string& expected) {
    const auto token = tokens_.next();
    if (!token) fail(tokens_.last_line(), "unexpected end of file, expected " + expected);
    return *token;
  }

  /// Fails for `token`, which is not a finite number; `what` names it.
  [[noreturn]] void bad_number(const BvhToken& token, const std::string& what) const {
    const char* problem = text::to_double(token.text) ? " is not finite" : " is not a number";
    fail(token.line, what + ": " + bvh_quote(token.text) + problem);
  }

  /// `token` as a finite number; `what` names it in errors.
  double finite_number(const BvhToken& token, const std::string& what) const {
    const auto value = bvh_finite(token.text);
    if (!value) bad_number(token, what);
    return *value;
  }

  void parse_hierarchy() {
    const auto first = tokens_.next();
    if (!first) fail(1, "empty file, expected HIERARCHY");
    if (first->text != "HIERARCHY")
      fail(first->line, "expected HIERARCHY, found " + bvh_quote(first->text));
    const auto root = tokens_.next();
    if (!root || root->text == "MOTION") fail(tokens_.last_line(), "empty hierarchy: no ROOT");
    if (root->text != "ROOT") fail(root->line, "expected ROOT, found " + bvh_quote(root->text));
    open_joint(*root);
    while (!stack_.empty()) {
      const auto token = tokens_.next();
      if (!token)
        fail(tokens_.last_line(), "unexpected end of file: missing '}' of " +
                                      block_name(stack_.back()) + " (opened on line " +
                                      std::to_string(stack_.back().line) + ")");
      parse_statement(*token);
    }
  }

  void parse_statement(const BvhToken& token) {
    if (token.text == "OFFSET")
      parse_offset(token);
    else if (token.text == "CHANNELS")
      parse_channels(token);
    else if (token.text == "JOINT")
      open_joint(token);
    else if (token.text == "End")
      open_end_site(token);
    else if (token.text == "}")
      close_block(token);
    else if (token.text == "ROOT")
      fail(token.line, "a second ROOT (a BVH file has exactly one)");
    else if (token.text == "MOTION")
      fail(token.line, "MOTION inside " + block_name(stack_.back()) + ": missing '}'");
    else if (token.text == "{")
      fail(token.line, "unexpected '{' in " + block_name(stack_.back()));
    else
      fail(token.line,
           "unknown keyword " + bvh_quote(token.text) + " in " + block_name(stack_.back()));
  }

  void push(const Block& block) {
    if (stack_.size() >= kBvhMaxDepth)
      fail(block.line, "blocks nested deeper than " + std::to_string(kBvhMaxDepth));
    stack_.push_back(block);
  }

  void expect_open_brace(const std::string& after) {
    const BvhToken brace = next_or_fail("'{' after " + after);
    if (brace.text != "{")
      fail(brace.line, "expected '{' after " + after + ", found " + bvh_quote(brace.text));
  }

  /// ROOT name { or JOINT name {
  void open_joint(const BvhToken& keyword) {
    const std::string kind(keyword.text);
    if (!stack_.empty() && stack_.back().end_site)
      fail(keyword.line,
           "JOINT inside " + block_name(stack_.back()) + " (an End Site has no joints)");
    const auto name = tokens_.peek();
    if (!name || name->line != keyword.line || name->text == "{" || name->text == "}")
      fail(keyword.line, kind + " without a name");
    tokens_.next();
    if (!names_.emplace(name->text).second)
      fail(name->line, "duplicate joint name " + bvh_quote(name->text));
    expect_open_brace(kind + " " + bvh_quote(name->text));
    BvhJoint joint;
    joint.name = std::string(name->text);
    joint.parent = stack_.empty() ? -1 : stack_.back().joint;
    joint.first_channel = motion_.num_channels;
    if (!stack_.empty()) stack_.back().has_children = true;
    push(Block{static_cast<int>(motion_.joints.size()), false, keyword.line});
    motion_.joints.push_back(std::move(joint));
  }

  /// End Site {
  void open_end_site(const BvhToken& keyword) {
    const auto site = tokens_.peek();
    if (!site || site->line != keyword.line || site->text != "Site")
      fail(keyword.line, "unknown keyword \"End\" (expected \"End Site\")");
    tokens_.next();
    Block& owner = stack_.back();
    if (owner.end_site) fail(keyword.line, "End Site inside " + block_name(owner));
    owner.has_children = true;
    expect_open_brace("End Site");
    push(Block{owner.joint, true, keyword.line});
  }

  void close_block(const BvhToken& brace) {
    const Block& block = stack_.back();
    if (!block.has_offset) fail(brace.line, block_name(block) + " has no OFFSET");
    stack_.pop_back();
  }

  /// OFFSET x y z, all on one line.
  void parse_offset(const BvhToken& keyword) {
    Block& block = stack_.back();
    if (block.has_offset) fail(keyword.line, "a second OFFSET in " + block_name(block));
    const std::vector<BvhToken> values = tokens_.rest_of_line(keyword.line);
    if (values.size() != 3)
      fail(keyword.line, "OFFSET needs 3 numbers, found " + std::to_string(values.size()));
    Vec3 offset;
    for (int i = 0; i < 3; ++i)
      offset[i] = finite_number(values[static_cast<std::size_t>(i)], "OFFSET");
    if (!block.end_site) motion_.joints[static_cast<std::size_t>(block.joint)].offset = offset;
    block.has_offset = true;
  }

  /// CHANNELS n c1 .. cn, all on one line, before the joint's children.
  void parse_channels(const BvhToken& keyword) {
    Block& block = stack_.back();
    if (block.end_site)
      fail(keyword.line, "CHANNELS in " + block_name(block) + " (an End Site has none)");
    if (block.has_channels) fail(keyword.line, "a second CHANNELS in " + block_name(block));
    if (block.has_children)
      fail(keyword.line, "CHANNELS of " + block_name(block) + " after its child blocks");
    const std::vector<BvhToken> words = tokens_.rest_of_line(keyword.line);
    if (words.empty()) fail(keyword.line, "CHANNELS without a count");
    const auto count = text::to_int(words[0].text);
    if (!count || *count < 0 || *count > kBvhMaxJointChannels)
      fail(keyword.line,
           "the channel count must be an integer in 0..6, found " + bvh_quote(words[0].text));
    if (static_cast<std::int64_t>(words.size()) - 1 != *count)
      fail(keyword.line, "CHANNELS " + std::to_string(*count) + " but " +
                             std::to_string(words.size() - 1) + " channel names given");
    BvhJoint& joint = motion_.joints[static_cast<std::size_t>(block.joint)];
    for (std::size_t i = 1; i < words.size(); ++i) {
      const auto channel = bvh_channel(words[i].text);
      if (!channel) fail(keyword.line, "unknown channel " + bvh_quote(words[i].text));
      for (const BvhChannel seen : joint.channels)
        if (seen == *channel)
          fail(keyword.line, "channel " + bvh_quote(words[i].text) + " listed twice");
      joint.channels.push_back(*channel);
    }
    joint.first_channel = motion_.num_channels;
    motion_.num_channels += static_cast<int>(*count);
    block.has_channels = true;
  }

  void parse_motion() {
    const auto motion = tokens_.next();
    if (!motion) fail(tokens_.last_line(), "no MOTION section");
    if (motion->text == "ROOT") fail(motion->line, "a second ROOT (a BVH file has exactly one)");
    if (motion->text != "MOTION")
      fail(motion->line, "expected MOTION after the hierarchy, found " + bvh_quote(motion->text));
    const auto [frames, line] = parse_frame_count();
    parse_frame_time();
    parse_frames(frames, line);
  }

  /// Frames: N. Returns N and its line.
  std::pair<std::int64_t, int> parse_frame_count() {
    const BvhToken keyword = next_or_fail("\"Frames:\"");
    if (keyword.text != "Frames:")
      fail(keyword.line, "expected \"Frames:\", found " + bvh_quote(keyword.text));
    const BvhToken value = next_or_fail("the number of frames");
    const auto n = text::to_int(value.text);
    if (!n) fail(value.line, "Frames: " + bvh_quote(value.text) + " is not an integer");
    if (*n < 0) fail(value.line, "Frames: " + std::to_string(*n) + " is negative");
    if (*n > std::numeric_limits<int>::max())
      fail(value.line, "Frames: " + std::to_string(*n) + " is too many");
    return {*n, value.line};
  }

  /// Frame Time: t
  void parse_frame_time() {
    const BvhToken frame = next_or_fail("\"Frame Time:\"");
    const auto time = tokens_.next();
    if (frame.text != "Frame" || !time || time->text != "Time:")
      fail(frame.line, "expected \"Frame Time:\", found " + bvh_quote(frame.text));
    const BvhToken value = next_or_fail("the frame time");
    const double t = finite_number(value, "Frame Time");
    if (t <= 0.0) fail(value.line, "Frame Time must be > 0, found " + bvh_quote(value.text));
    motion_.frame_time = t;
  }

  /// The N × num_channels values; a shortfall is reported at `line`, that of "Frames:".
  /// Each value takes at least two bytes of text (a separator and a digit), so a count
  /// that the rest of the file cannot hold fails before `frames` is allocated.
  /// (N < 2^31 and num_channels < 2^31: the product does not overflow.)
  void parse_frames(std::int64_t n, int line) {
    const std::int64_t channels = motion_.num_channels;
    const std::int64_t expected = n * channels;
    const auto capacity = static_cast<std::int64_t>(tokens_.remaining_bytes() / 2);
    if (expected > capacity) fail(line, missing_values(n, channels, tokens_.count_remaining()));
    motion_.frames.resize(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(channels));
    for (std::int64_t i = 0; i < expected; ++i) {
      const auto token = tokens_.next();
      if (!token) fail(line, missing_values(n, channels, i));
      const std::int64_t frame = i / channels;
      const auto value = bvh_finite(token->text);
      if (!value) bad_number(*token, "frame " + std::to_string(frame + 1));
      motion_.frames(frame, i % channels) = *value;
    }
    if (const auto extra = tokens_.next())
      fail(extra->line, "extra data after the last frame: " + bvh_quote(extra->text) + " (" +
                            std::to_string(expected) + " values expected)");
  }

  static std::string missing_values(std::int64_t n, std::int64_t channels, std::int64_t found) {
    return "the frames end early: expected " + std::to_string(n * channels) + " values (" +
           std::to_string(n) + " frames x " + std::to_string(channels) + " channels), found " +
           std::to_string(found);
  }

  BvhTokens tokens_;
  BvhMotion motion_;
  std::vector<Block> stack_;
  std::unordered_set<std::string_view> names_;
};

}  // namespace

int BvhMotion::find(const std::string& name) const {
  for (std::size_t i = 0; i < joints.size(); ++i)
    if (joints[i].name == name) return static_cast<int>(i);
  return -1;
}

Mat3 BvhMotion::local_rotation(int joint, int frame) const {
  if (joint < 0 || joint >= static_cast<int>(joints.size()))
    throw std::out_of_range("BvhMotion::local_rotation: joint " + std::to_string(joint) + " of " +
                            std::to_string(joints.size()));
  if (frame < 0 || frame >= num_frames())
    throw std::out_of_range("BvhMotion::local_rotation: frame " + std::to_string(frame) + " of " +
                            std::to_string(num_frames()));
  const BvhJoint& j = joints[static_cast<std::size_t>(joint)];
  const auto channels = static_cast<Eigen::Index>(j.channels.size());
  if (j.first_channel < 0 || j.first_channel + channels > frames.cols())
    throw std::out_of_range("BvhMotion::local_rotation: the channels of joint \"" + j.name +
                            "\" lie outside the frames");
  Mat3 r = Mat3::Identity();
  for (Eigen::Index k = 0; k < channels; ++k) {
    const int axis = bvh_rotation_axis(j.channels[static_cast<std::size_t>(k)]);
    if (axis >= 0) r = r * bvh_axis_rotation(axis, frames(frame, j.first_channel + k));
  }
  return r;
}

BvhMotion parse_bvh(std::string_view text, const std::string& source) {
  constexpr std::string_view kByteOrderMark = "\xEF\xBB\xBF";
  if (text.starts_with(kByteOrderMark)) text.remove_prefix(kByteOrderMark.size());
  return BvhParser(text, source).parse();
}

BvhMotion read_bvh(const std::filesystem::path& path) {
  return parse_bvh(text::read_file(path), path.string());
}

}  // namespace tightfit
