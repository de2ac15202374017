#include "analysis/thickness_statistics.hpp"

#include <algorithm>
#include <map>
#include <numeric>
#include <utility>

#include "core/errors.hpp"
#include "geometry/face_adjacency.hpp"
#include "geometry/union_find.hpp"

namespace bemshape::analysis {

double weighted_quantile(const Eigen::VectorXd& values, const Eigen::VectorXd& areas, double p) {
  std::vector<Eigen::Index> order(static_cast<std::size_t>(values.size()));
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  std::sort(order.begin(), order.end(),
            [&](Eigen::Index i, Eigen::Index j) { return values(i) < values(j); });
  const double total = areas.sum();
  double before = 0.0;
  double previous_position = 0.0, previous_value = values(order.front());
  for (std::size_t k = 0; k < order.size(); ++k) {
    const Eigen::Index i = order[k];
    const double position = (before + 0.5 * areas(i)) / total;
    if (p <= position) {
      if (k == 0 || position <= previous_position)
        return values(i);
      const double w = (p - previous_position) / (position - previous_position);
      return (1.0 - w) * previous_value + w * values(i);
    }
    before += areas(i);
    previous_position = position;
    previous_value = values(i);
  }
  return previous_value;
}

ThicknessStatistics thickness_statistics(const geometry::SurfaceMesh& mesh,
                                         const Eigen::VectorXd& thickness,
                                         double unmeasurable_from) {
  std::vector<Eigen::Index> measured;
  ThicknessStatistics stats;
  for (Eigen::Index f = 0; f < mesh.num_faces(); ++f) {
    if (measurable_face(mesh, thickness, f, unmeasurable_from))
      measured.push_back(f);
    else
      stats.unmeasurable_area += mesh.face_areas()(f);
  }
  if (measured.empty())
    throw InputError(
        "no part of the surface has a measurable thickness at this h0 (every face "
        "is farther than the PDE reaches from an opposite wall); choose h0 near the "
        "wall thickness of interest");
  const auto m = static_cast<Eigen::Index>(measured.size());
  Eigen::VectorXd values(m), areas(m);
  for (Eigen::Index k = 0; k < m; ++k) {
    values(k) = thickness(measured[static_cast<std::size_t>(k)]);
    areas(k) = mesh.face_areas()(measured[static_cast<std::size_t>(k)]);
  }
  Eigen::Index thinnest = 0;
  stats.minimum = values.minCoeff(&thinnest);
  stats.maximum = values.maxCoeff();
  stats.min_location = mesh.face_centroids().row(measured[static_cast<std::size_t>(thinnest)]);
  stats.measured_area = areas.sum();
  stats.mean = values.dot(areas) / stats.measured_area;
  stats.median = weighted_quantile(values, areas, 0.5);
  stats.p05 = weighted_quantile(values, areas, 0.05);
  stats.p95 = weighted_quantile(values, areas, 0.95);
  return stats;
}

namespace {

/// The edge-connected sets of faces whose value is `selected`, joined also across the wall
/// where `across` (#F or empty) names a selected face; `more_severe(t, e)` says
/// whether value t is more severe than the region's extreme e so far (lower for thin, higher
/// for thick), kept in the members `extreme` and `location`.
template <class Region, class Selected, class MoreSevere>
std::vector<Region> connected_regions(const geometry::SurfaceMesh& mesh,
                                      const Eigen::VectorXd& thickness,
                                      const Eigen::VectorXi& across, Selected selected,
                                      MoreSevere more_severe, double Region::*extreme,
                                      Eigen::Vector3d Region::*location) {
  const Eigen::Index nf = mesh.num_faces();
  // Union-find over the selected faces joined through shared edges.
  const std::vector<std::vector<int>> neighbours = geometry::edge_neighbours(mesh.faces());
  geometry::UnionFind sets(static_cast<std::size_t>(nf));
  for (Eigen::Index f = 0; f < nf; ++f) {
    if (!selected(thickness(f)))
      continue;
    for (int g : neighbours[static_cast<std::size_t>(f)])
      if (selected(thickness(g)))
        sets.unite(static_cast<int>(f), g);
    if (across.size() == nf && across(f) >= 0 && selected(thickness(across(f))))
      sets.unite(static_cast<int>(f), across(f));
  }
  const auto root = [&sets](Eigen::Index f) { return Eigen::Index{sets.find(static_cast<int>(f))}; };
  std::map<Eigen::Index, Region> by_root;
  for (Eigen::Index f = 0; f < nf; ++f) {
    if (!selected(thickness(f)))
      continue;
    Region& region = by_root[root(f)];
    const double area = mesh.face_areas()(f);
    const Eigen::Vector3d centroid = mesh.face_centroids().row(f);
    if (region.faces == 0 || more_severe(thickness(f), region.*extreme)) {
      region.*extreme = thickness(f);
      region.*location = centroid;
      region.extreme_face = static_cast<int>(f);
    }
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d corner = mesh.vertices().row(mesh.faces()(f, k)).transpose();
      region.box_min = region.faces == 0 && k == 0 ? corner : region.box_min.cwiseMin(corner);
      region.box_max = region.faces == 0 && k == 0 ? corner : region.box_max.cwiseMax(corner);
    }
    ++region.faces;
    region.face_indices.push_back(static_cast<int>(f));
    region.area += area;
    region.centroid += area * centroid;
  }
  std::vector<Region> regions;
  for (auto& [key, region] : by_root) {
    if (region.area > 0.0)
      region.centroid /= region.area;
    regions.push_back(region);
  }
  std::sort(regions.begin(), regions.end(), [&](const Region& x, const Region& y) {
    return x.*extreme != y.*extreme ? more_severe(x.*extreme, y.*extreme) : x.area > y.area;
  });
  return regions;
}

}  // namespace

std::vector<ThinRegion> thin_regions(const geometry::SurfaceMesh& mesh,
                                     const Eigen::VectorXd& thickness, double threshold,
                                     const Eigen::VectorXi& across) {
  return connected_regions<ThinRegion>(
      mesh, thickness, across, [threshold](double t) { return t < threshold; },
      [](double t, double extreme) { return t < extreme; }, &ThinRegion::minimum,
      &ThinRegion::min_location);
}

std::vector<ThickRegion> thick_regions(const geometry::SurfaceMesh& mesh,
                                       const Eigen::VectorXd& thickness, double threshold,
                                       double unmeasurable_from,
                                       const Eigen::VectorXi& across) {
  return connected_regions<ThickRegion>(
      mesh, thickness, across,
      [threshold, unmeasurable_from](double t) { return t > threshold && t < unmeasurable_from; },
      [](double t, double extreme) { return t > extreme; }, &ThickRegion::maximum,
      &ThickRegion::max_location);
}

double speck_area(std::optional<double> requested, double h0, double part_area) {
  return std::min(requested.value_or(kSpeckArea * h0 * h0), kSpeckPartFraction * part_area);
}

ThinCheck thin_check(std::vector<ThinRegion>& regions, double speck_area) {
  ThinCheck check;
  check.speck_area = speck_area;
  std::vector<ThinRegion> listed;
  for (ThinRegion& r : regions) {
    check.thin_area += r.area;
    if (r.area < speck_area) {
      check.speck_total += r.area;
      check.specks.push_back(std::move(r));
    } else {
      listed.push_back(std::move(r));
    }
  }
  regions = std::move(listed);
  check.pass = check.thin_area == 0.0 || check.thin_area < speck_area;
  return check;
}

}  // namespace bemshape::analysis
