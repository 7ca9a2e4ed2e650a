#include "tightfit/body/body_builder.hpp"

#include "tightfit/body/surface_distance.hpp"
#include "tightfit/common/stopwatch.hpp"
#include "tightfit/geometry/mesh_measures.hpp"

namespace tightfit {
namespace {

void record_input(const TriMesh& surface, BuildReport* report) {
  if (!report) return;
  report->input_vertices = surface.num_vertices();
  report->input_faces = surface.num_faces();
  report->input_volume = signed_volume(surface);
  report->input_area = surface_area(surface);
}

}  // namespace

double BuildReport::total_seconds() const {
  double total = 0.0;
  for (const auto& [name, s] : stage_seconds) total += s;
  return total;
}

VolumeOptions default_volume_options(double edge_length) {
  VolumeOptions o;
  o.quality.max_volume = regular_tet_volume(2.0 * edge_length);
  o.core.soft_tissue = 0.015;
  o.core.bone_sample_spacing = edge_length;
  o.core.bone_sample_clearance = 0.5 * edge_length;
  return o;
}

Body body_from_surface(const TriMesh& surface, const VolumeOptions& options, BuildReport* report) {
  Stopwatch clock;
  const SurfaceDistance distance(surface);
  const Points3 bone_points = bone_sample_points(options.core, distance);
  Body body;
  body.surface = surface;
  body.volume =
      tetrahedralize_surface(surface, options.quality, bone_points, options.core.embedded_core);
  if (report) {
    report->bone_points = static_cast<int>(bone_points.rows());
    report->tetgen_switches = tetgen_switches(options.quality);
    report->add_stage("tetrahedralize", clock.lap());
  }
  body.pinned =
      pinned_core(body.volume, surface.num_vertices(), distance, options.core,
                  options.core.embedded_core.num_vertices() + static_cast<int>(bone_points.rows()));
  if (report) report->add_stage("core", clock.lap());
  return body;
}

namespace {

template <class Params, class Surface>
TriMesh generated(const Params& params, BuildReport* report, Surface make_surface) {
  Stopwatch clock;
  LimitFitResult fit;
  TriMesh surface = make_surface(params, &fit);
  if (report) {
    record_input(surface, report);
    report->limit_fitted = params.fit_limit;
    report->limit_fit = fit;
    report->add_stage("generate", clock.lap());
  }
  return surface;
}

double edge_of(double edge_length, double radius) {
  return edge_length > 0.0 ? edge_length : default_generator_edge_length(radius);
}

}  // namespace

TriMesh generated_surface(const CylinderParams& params, BuildReport* report) {
  return generated(params, report, cylinder_surface);
}

TriMesh generated_surface(const SphereParams& params, BuildReport* report) {
  return generated(params, report, sphere_surface);
}

Body cylinder_body(const CylinderParams& params, BuildReport* report) {
  return cylinder_body(params, default_volume_options(edge_of(params.edge_length, params.radius)),
                       report);
}

Body cylinder_body(const CylinderParams& params, const VolumeOptions& options,
                   BuildReport* report) {
  return body_from_surface(generated_surface(params, report), options, report);
}

Body sphere_body(const SphereParams& params, BuildReport* report) {
  return sphere_body(params, default_volume_options(edge_of(params.edge_length, params.radius)),
                     report);
}

Body sphere_body(const SphereParams& params, const VolumeOptions& options, BuildReport* report) {
  return body_from_surface(generated_surface(params, report), options, report);
}

}  // namespace tightfit
