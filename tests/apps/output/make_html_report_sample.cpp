// make_html_report_sample FACES OUT.html: an HTML thickness report of a synthetic part, for the
// browser test and for measuring the page's size and load time at large face counts without
// a solve. The part is a geodesic sphere of radius 50 with about FACES faces (20·n², n the
// nearest frequency); its "thickness" is the smooth field
//
//   t(x) = 6 + 4·z/R + 1.5·sin(3·atan2(y, x))   [units]
//
// on the vertices, each face taking the mean of its corners. The thin regions below 4 and
// the histogram and the verdict (with a speck area of 0) come from the same functions as
// `bemshape thickness --html`.
#include <cmath>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <string>

#include "apps/output/html_report.hpp"
#include "apps/thickness_html_report.hpp"
#include "analysis/thickness_statistics.hpp"
#include "geometry/primitive_meshes.hpp"

int main(int argc, char** argv) {
  using namespace bemshape;
  if (argc != 3) {
    std::cerr << "usage: make_html_report_sample FACES OUT.html\n";
    return 2;
  }
  try {
    constexpr double radius = 50.0, threshold = 4.0;
    const double faces = std::stod(argv[1]);
    const int frequency = std::max(1, static_cast<int>(std::lround(std::sqrt(faces / 20.0))));
    const geometry::SurfaceMesh mesh = geometry::make_geodesic_sphere(radius, frequency);
    Eigen::VectorXd vertex_values(mesh.num_vertices());
    for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v) {
      const Eigen::Vector3d p = mesh.vertices().row(v);
      vertex_values(v) = 6.0 + 4.0 * p.z() / radius + 1.5 * std::sin(3.0 * std::atan2(p.y(), p.x()));
    }
    Eigen::VectorXd face_values(mesh.num_faces());
    for (Eigen::Index f = 0; f < mesh.num_faces(); ++f)
      face_values(f) = (vertex_values(mesh.faces()(f, 0)) + vertex_values(mesh.faces()(f, 1)) +
                        vertex_values(mesh.faces()(f, 2))) / 3.0;
    apps::ThicknessHtmlInput input;
    input.title = "synthetic sphere, " + std::to_string(mesh.num_faces()) + " faces";
    input.measure = "h_p";
    input.mesh = &mesh;
    input.vertex_thickness = vertex_values;
    input.face_thickness = face_values;
    input.unmeasurable_from = 1e6;
    input.statistics = analysis::thickness_statistics(mesh, face_values, input.unmeasurable_from);
    input.thin_regions = analysis::thin_regions(mesh, face_values, threshold);
    input.check = analysis::thin_check(input.thin_regions, 0.0);  // every region listed
    input.min_thickness = threshold;
    input.parameters = {{"part", "geodesic sphere, radius 50"},
                        {"frequency", std::to_string(frequency)},
                        {"thickness", "6 + 4 z/R + 1.5 sin(3 atan2(y, x))"}};
    output::write_html_report(argv[2], apps::thickness_html_report(input));
    std::cout << mesh.num_faces() << " faces, " << input.thin_regions.size() << " thin regions\n";
  } catch (const std::exception& e) {
    std::cerr << "make_html_report_sample: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
