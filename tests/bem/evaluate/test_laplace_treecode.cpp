// bem/evaluate/laplace_treecode.hpp and yukawa_cutoff_sum.hpp against the direct sums over
// every panel, on a ball and on a hollow box, at random points inside, outside and within
// 1% of a panel diameter of the surface; the treecode's error falls as p grows and θ
// shrinks; evaluate_potential gives the direct path's results.
#include <algorithm>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include "bem/hmatrix/cluster_tree.hpp"
#include "bem/evaluate/laplace_treecode.hpp"
#include "bem/evaluate/yukawa_cutoff_sum.hpp"
#include "bem/kernels/laplace_kernel.hpp"
#include "bem/quadrature/panel_integrals.hpp"
#include "bem/evaluate/potential_evaluation.hpp"
#include "bem/kernels/yukawa_kernel.hpp"
#include "core/errors.hpp"
#include "geometry/primitive_meshes.hpp"

using namespace bemshape;

namespace {

/// The boundary data of s(x) = x, harmonic inside: φ_i = x_i at the centroids, q_i = n_i.
/// The interior representation formula reproduces s = x up to the discretisation error.
struct Densities {
  Eigen::MatrixX3d q, phi;
};
Densities linear_field(const geometry::SurfaceMesh& mesh) {
  return {mesh.face_normals(), mesh.face_centroids()};
}

/// Hollow cube: outer side 1, wall 0.15, edges ≤ 1/12 (2,700 faces).
geometry::SurfaceMesh hollow_box() {
  return geometry::make_hollow_box(Eigen::Vector3d::Constant(0.5), 0.15, 1.0 / 12);
}

/// `n` uniform points in the cube [−0.6, 0.6]³ (inside and outside both solids) and, for
/// every `stride`-th face, the points 1% of its diameter above and below its centroid and
/// below one of its corners.
Eigen::MatrixX3d test_points(const geometry::SurfaceMesh& mesh, int n, unsigned seed,
                             Eigen::Index stride = 13) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.6, 0.6);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < n; ++i)
    points.emplace_back(u(rng), u(rng), u(rng));
  for (Eigen::Index f = 0; f < mesh.num_faces(); f += stride) {
    const Eigen::Vector3d c = mesh.face_centroids().row(f).transpose();
    const Eigen::Vector3d normal = mesh.face_normals().row(f).transpose();
    const double h = (mesh.corner(f, 1) - mesh.corner(f, 0)).norm();
    points.push_back(c + 0.01 * h * normal);
    points.push_back(c - 0.01 * h * normal);
    points.push_back(0.9 * mesh.corner(f, 0) + 0.1 * c - 0.01 * h * normal);
  }
  Eigen::MatrixX3d p(static_cast<Eigen::Index>(points.size()), 3);
  for (size_t i = 0; i < points.size(); ++i)
    p.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  return p;
}

struct Sums {
  Eigen::MatrixX3d s;
  Eigen::MatrixXd gradient;  ///< #P×9
  Eigen::VectorXd winding;
};

Sums direct_laplace(const std::vector<bem::Panel>& panels, const Densities& d,
                    const Eigen::MatrixX3d& points) {
  const bem::LaplaceKernel laplace{};
  Sums out{Eigen::MatrixX3d::Zero(points.rows(), 3), Eigen::MatrixXd::Zero(points.rows(), 9),
           Eigen::VectorXd::Zero(points.rows())};
#pragma omp parallel for schedule(dynamic, 4)
  for (Eigen::Index p = 0; p < points.rows(); ++p) {
    Eigen::Matrix3d g = Eigen::Matrix3d::Zero();
    for (size_t k = 0; k < panels.size(); ++k) {
      const auto l = bem::integrate_panel(laplace, panels[k], points.row(p).transpose(), true);
      const auto f = static_cast<Eigen::Index>(k);
      out.winding(p) -= l.double_layer;
      out.s.row(p) += l.single_layer * d.q.row(f) - l.double_layer * d.phi.row(f);
      g += d.q.row(f).transpose() * l.single_layer_gradient.transpose() -
           d.phi.row(f).transpose() * l.double_layer_gradient.transpose();
    }
    for (int i = 0; i < 9; ++i)
      out.gradient(p, i) = g(i / 3, i % 3);
  }
  return out;
}

Sums treecode_laplace(const std::vector<bem::Panel>& panels, const bem::ClusterTree& tree,
                      const Densities& d, const Eigen::MatrixX3d& points,
                      bem::LaplaceTreecodeParameters parameters, bem::TreecodeCounts& counts) {
  const bem::LaplaceTreecode treecode(panels, tree, d.q, d.phi, parameters);
  auto workspace = treecode.workspace();
  Sums out{Eigen::MatrixX3d(points.rows(), 3), Eigen::MatrixXd(points.rows(), 9),
           Eigen::VectorXd(points.rows())};
  for (Eigen::Index p = 0; p < points.rows(); ++p) {
    const auto v = treecode.evaluate(points.row(p).transpose(), workspace, counts);
    out.s.row(p) = v.s;
    out.winding(p) = v.winding;
    for (int i = 0; i < 9; ++i)
      out.gradient(p, i) = v.gradient(i / 3, i % 3);
  }
  return out;
}

/// Largest error over the points, relative to the largest value (s, ∇s) or absolute (the
/// winding number, of order 1).
struct Errors {
  double s = 0, gradient = 0, winding = 0;
  double max() const { return std::max({s, gradient, winding}); }
};
Errors errors(const Sums& reference, const Sums& approximation) {
  return {(reference.s - approximation.s).rowwise().norm().maxCoeff() /
              reference.s.rowwise().norm().maxCoeff(),
          (reference.gradient - approximation.gradient).rowwise().norm().maxCoeff() /
              reference.gradient.rowwise().norm().maxCoeff(),
          (reference.winding - approximation.winding).cwiseAbs().maxCoeff()};
}

struct Case {
  const char* name;
  geometry::SurfaceMesh mesh;
};

}  // namespace

TEST_CASE(
    "treecode: s and grad s and winding within 1e-6 of the direct sums on a ball and a hollow "
    "box") {
  for (const Case& c :
       {Case{"ball", geometry::make_geodesic_sphere(0.5, 10)}, Case{"hollow box", hollow_box()}}) {
    const auto panels = bem::make_panels(c.mesh);
    const bem::ClusterTree tree(panels, 16);
    const Densities d = linear_field(c.mesh);
    const Eigen::MatrixX3d points = test_points(c.mesh, 300, 3);
    const Sums reference = direct_laplace(panels, d, points);
    bem::TreecodeCounts counts;
    const auto parameters = bem::LaplaceTreecodeParameters::for_tolerance(1e-6);
    const Errors e =
        errors(reference, treecode_laplace(panels, tree, d, points, parameters, counts));
    INFO(c.name << ": " << c.mesh.num_faces() << " faces, " << points.rows() << " points, errors s "
                << e.s << ", gradient " << e.gradient << ", winding " << e.winding);
    CHECK(e.max() <= 1e-6);
    // The tree does less work than the direct sum, whose cost is #P × #F panel integrals
    // (on these small meshes about a third; docs/benchmarks.md has larger ones).
    CHECK(counts.panel_integrals + counts.expansions <
          std::uint64_t(points.rows() * c.mesh.num_faces()) / 2);
    // Inside points see s = x (the data's harmonic extension), to the discretisation error.
    for (Eigen::Index p = 0; p < points.rows(); ++p)
      if (reference.winding(p) > 0.5)
        CHECK(reference.winding(p) == Approx(1.0).margin(1e-6));
  }
}

TEST_CASE("treecode: the error falls as the order p grows and as theta shrinks") {
  const auto mesh = hollow_box();
  const auto panels = bem::make_panels(mesh);
  const bem::ClusterTree tree(panels, 16);
  const Densities d = linear_field(mesh);
  const Eigen::MatrixX3d points = test_points(mesh, 200, 5);
  const Sums reference = direct_laplace(panels, d, points);
  double previous = 1.0;
  for (int p : {0, 2, 4, 6, 8, 10}) {
    bem::TreecodeCounts counts;
    const double e =
        errors(reference, treecode_laplace(panels, tree, d, points, {p, 0.5}, counts)).max();
    INFO("p = " << p << ", theta = 0.5: error " << e);
    CHECK(e < 0.5 * previous);
    previous = e;
  }
  previous = 1.0;
  for (double theta : {0.8, 0.6, 0.4, 0.2}) {
    bem::TreecodeCounts counts;
    const double e =
        errors(reference, treecode_laplace(panels, tree, d, points, {4, theta}, counts)).max();
    INFO("p = 4, theta = " << theta << ": error " << e);
    CHECK(e < 0.5 * previous);
    previous = e;
  }
}

TEST_CASE("treecode: parameters outside their ranges are refused") {
  const auto mesh = geometry::make_geodesic_sphere(0.5, 2);
  const auto panels = bem::make_panels(mesh);
  const bem::ClusterTree tree(panels, 4);
  const Densities d = linear_field(mesh);
  CHECK_THROWS_AS(bem::LaplaceTreecode(panels, tree, d.q, d.phi, {-1, 0.5}), InputError);
  CHECK_THROWS_AS(bem::LaplaceTreecode(panels, tree, d.q, d.phi, {40, 0.5}), InputError);
  CHECK_THROWS_AS(bem::LaplaceTreecode(panels, tree, d.q, d.phi, {4, 1.0}), InputError);
}

TEST_CASE(
    "Yukawa cutoff sum: the direct exterior sums within 1e-9 with the panels beyond the cutoff "
    "skipped") {
  const auto mesh = hollow_box();
  const auto panels = bem::make_panels(mesh);
  const bem::ClusterTree tree(panels, 16);
  const Densities d = linear_field(mesh);
  const double kappa = 33.0;  // κ·h = 2.8; the cutoff gap 23/κ ≈ 0.7 is less than the box
  const bem::YukawaKernel yukawa{kappa};
  const bem::YukawaCutoffSum sum(panels, tree, kappa, d.q, d.phi, 1e-10);
  const Eigen::MatrixX3d points = test_points(mesh, 100, 9, 53);
  std::vector<int> stack;
  std::uint64_t used = 0;
  double largest = 0.0, error = 0.0;
  for (Eigen::Index p = 0; p < points.rows(); ++p) {
    const Eigen::Vector3d x = points.row(p).transpose();
    Eigen::RowVector3d s = Eigen::RowVector3d::Zero();
    Eigen::Matrix3d g = Eigen::Matrix3d::Zero();
    for (size_t k = 0; k < panels.size(); ++k) {
      const auto y = bem::integrate_panel(yukawa, panels[k], x, true);
      const auto f = static_cast<Eigen::Index>(k);
      s += -y.single_layer * d.q.row(f) + y.double_layer * d.phi.row(f);
      g += -d.q.row(f).transpose() * y.single_layer_gradient.transpose() +
           d.phi.row(f).transpose() * y.double_layer_gradient.transpose();
    }
    const auto v = sum.evaluate(x, stack, used);
    largest = std::max({largest, s.norm(), g.norm()});
    error = std::max({error, (v.s - s).norm(), (v.gradient - g).norm()});
  }
  INFO("largest " << largest << ", error " << error << ", panels used " << used);
  CHECK(error <= 1e-9 * largest);
  CHECK(used < std::uint64_t(points.rows() * mesh.num_faces()) / 2);
}

TEST_CASE("evaluate_potential: the tree gives the direct path's s and grad s and inside flags") {
  const auto mesh = hollow_box();
  bem::BoundarySolution solution;
  const Densities d = linear_field(mesh);
  solution.phi = d.phi;
  solution.q = d.q;
  // κ·h = 2.8 for h0 = 0.3: the default element size rule (κ·h = 3).
  solution.parameters = bem::TransmissionParameters::from_shape(0.3, 0.2);
  const Eigen::MatrixX3d points = test_points(mesh, 60, 13, 53);
  bem::PotentialEvaluationOptions direct;
  direct.direct = true;
  const auto reference = bem::evaluate_potential(mesh, solution, points, {}, direct);
  const auto fast = bem::evaluate_potential(mesh, solution, points);
  CHECK(reference.inside == fast.inside);
  const double s_error =
      (reference.s - fast.s).rowwise().norm().maxCoeff() / reference.s.rowwise().norm().maxCoeff();
  const double g_error = (reference.gradient - fast.gradient).rowwise().norm().maxCoeff() /
                         reference.gradient.rowwise().norm().maxCoeff();
  INFO("s " << s_error << ", gradient " << g_error);
  CHECK(s_error <= 1e-6);
  CHECK(g_error <= 1e-6);
  CHECK(reference.cost.laplace_expansions == 0);
  CHECK(fast.cost.laplace_expansions > 0);
  CHECK(fast.cost.laplace_panel_integrals + fast.cost.laplace_expansions <
        reference.cost.laplace_panel_integrals / 2);
}
