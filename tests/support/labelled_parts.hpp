#pragma once
// CAD-like parts whose walls are known by design, for measuring what a wall-thickness tool
// reports against what the part's designer would say: plates with holes, an L-bracket with a
// thin gusset rib, a tube, a plate with a solid boss and a thin tab, a tray with a thinned
// pocket, a bent sheet bracket, a filleted T-junction, a tapered wall, and a large
// thin-walled tray with ribs and bosses (356 x 356 x 60, 3 mm walls: at h0 = 3 its default
// solver mesh has over a million faces, the size where memory decides whether a run fits).
//
// Each part comes with a classifier that labels any point of its surface (with the outward
// normal there) by the role of the wall it belongs to, so that any triangulation of the part —
// its own faces or a remeshed solver mesh — can be labelled face by face from the centroids:
//
//   nominal        a broad face of a wall of the design thickness (the part's nominal wall,
//                  or the local thickness of a tapered wall)
//   rim            an end face or a hole wall closing a wall: its design thickness is the
//                  thickness of the wall it closes
//   thin_feature   any face of a feature designed thinner than the nominal wall (rib, tab,
//                  thinned pocket); `feature` indexes LabelledPart::features
//   thick_feature  any face of a feature designed thicker (a solid boss)
//   junction       where walls meet (corners of an L, fillets, under a boss): no single
//                  design thickness
//
// Lengths in millimetres (model units); every part lies in the positive octant.

#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "geometry/surface_mesh.hpp"

namespace bemshape::testing {

enum class WallRole { nominal, rim, thin_feature, thick_feature, junction };

/// "nominal", "rim", "thin feature", "thick feature", "junction".
const char* to_string(WallRole role);

struct WallLabel {
  WallRole role = WallRole::junction;
  /// Design thickness of the wall the point belongs to [mm]; NaN for junctions.
  double thickness = 0.0;
  /// Index into LabelledPart::features for thin and thick features, else −1.
  int feature = -1;
};

/// A thin or thick feature of a part, for checking where a tool locates it.
struct PartFeature {
  std::string name;
  WallRole role = WallRole::thin_feature;
  double thickness = 0.0;  ///< design thickness [mm]
  geometry::BoundingBox box;         ///< the feature's material lies inside this box [mm]
};

struct LabelledPart {
  std::string name;
  std::string description;
  geometry::SurfaceMesh mesh;             ///< closed, outward-oriented
  double nominal_wall = 0.0;    ///< the part's nominal wall [mm]
  std::vector<PartFeature> features;
  /// Label of the surface point `x` with outward normal `n` (unit) [mm].
  std::function<WallLabel(const Eigen::Vector3d& x, const Eigen::Vector3d& n)> label;

  /// Labels of every face of `surface` (any triangulation of this part) from its centroid and
  /// normal.
  std::vector<WallLabel> label_faces(const geometry::SurfaceMesh& surface) const;
};

/// Names accepted by make_labelled_part, in a fixed order.
std::vector<std::string> labelled_part_names();

/// The part called `name`; InputError for an unknown name (the message lists the names).
/// `circle_segments` is the number of facets of every full circle (holes, tube, boss); the
/// default 64 is a typical CAD export's tessellation of these sizes.
LabelledPart make_labelled_part(const std::string& name, int circle_segments = 64);

}  // namespace bemshape::testing
