// make_test_mesh: writes the closed-form solids of the tests (geometry/primitive_meshes.hpp)
// as binary STL, for reproducing a test's bemshape run by hand:
//
//   make_test_mesh sphere RADIUS MAX_EDGE OUT.stl
//   make_test_mesh shell INNER_RADIUS OUTER_RADIUS MAX_EDGE OUT.stl   (cavity inside)
//   make_test_mesh box LX LY LZ MAX_EDGE OUT.stl        (centred at the origin)
//   make_test_mesh hollow-box SIDE WALL MAX_EDGE OUT.stl (a cube of side SIDE with a cubic
//                                                          cavity: walls WALL thick)
//   make_test_mesh cylinder RADIUS LENGTH MAX_EDGE OUT.stl
//   make_test_mesh part NAME OUT.stl [CIRCLE_SEGMENTS]     (tests/support/labelled_parts.hpp)
//   make_test_mesh damaged NAME OUT.stl [INTACT.stl]       (tests/support/damaged_meshes.hpp:
//                                                          the damaged mesh, and its intact part)
//   make_test_mesh damaged-list                            (the corpus, one mesh a line, tab-
//                         separated: name, expected outcome, wall, h0, max_edge, the damaged
//                         region's centre x y z and size, description; bench/bench_damaged_meshes.py)
#include <cstdlib>
#include <iostream>
#include <string>

#include "apps/output/stl_writer.hpp"
#include "tests/support/damaged_meshes.hpp"
#include "tests/support/labelled_parts.hpp"
#include "geometry/primitive_meshes.hpp"

int main(int argc, char** argv) {
  using namespace bemshape;
  const std::string kind = argc > 1 ? argv[1] : "";
  const auto arg = [&](int i) { return std::atof(argv[i]); };
  geometry::SurfaceMesh mesh;
  std::string out;
  if (kind == "sphere" && argc == 5) {
    mesh = geometry::make_geodesic_sphere(arg(2),
                                          geometry::geodesic_frequency_for_edge(arg(2), arg(3)));
    out = argv[4];
  } else if (kind == "box" && argc == 7) {
    const Eigen::Vector3d half(arg(2) / 2, arg(3) / 2, arg(4) / 2);
    mesh = geometry::make_box(-half, half, arg(5));
    out = argv[6];
  } else if (kind == "hollow-box" && argc == 6 && arg(3) > 0 && 2 * arg(3) < arg(2)) {
    mesh = geometry::make_hollow_box(Eigen::Vector3d::Constant(arg(2) / 2), arg(3), arg(4));
    out = argv[5];
  } else if (kind == "shell" && argc == 6) {
    mesh = geometry::make_spherical_shell(arg(2), arg(3),
                                          geometry::geodesic_frequency_for_edge(arg(2), arg(4)),
                                          geometry::geodesic_frequency_for_edge(arg(3), arg(4)));
    out = argv[5];
  } else if (kind == "cylinder" && argc == 6) {
    mesh = geometry::make_cylinder(arg(2), arg(3), arg(4));
    out = argv[5];
  } else if (kind == "part" && (argc == 4 || argc == 5)) {
    mesh = testing::make_labelled_part(argv[2], argc == 5 ? std::atoi(argv[4]) : 64).mesh;
    out = argv[3];
  } else if (kind == "damaged" && (argc == 4 || argc == 5)) {
    const testing::DamagedMesh d = testing::damaged_mesh(argv[2]);
    output::write_binary_stl(argv[3], d.vertices, d.faces);
    std::cout << argv[3] << ": " << d.faces.rows() << " faces, " << d.description << "; expected: "
              << testing::to_string(d.outcome) << '\n';
    if (argc == 4)
      return 0;
    mesh = d.intact;
    out = argv[4];
  } else if (kind == "damaged-list" && argc == 2) {
    std::cout.precision(17);
    for (const testing::DamagedMesh& d : testing::damaged_meshes())
      std::cout << d.name << '\t' << testing::to_string(d.outcome) << '\t' << d.wall << '\t'
                << d.h0 << '\t' << d.max_edge << '\t' << d.site.x() << '\t' << d.site.y() << '\t'
                << d.site.z() << '\t' << d.size << '\t' << d.description << '\n';
    return 0;
  } else {
    std::cerr
        << "usage: make_test_mesh sphere R EDGE OUT | shell R1 R2 EDGE OUT | box LX LY LZ EDGE "
           "OUT | hollow-box SIDE WALL EDGE OUT | cylinder R L EDGE OUT | part NAME OUT [SEGMENTS] | "
           "damaged NAME OUT [INTACT_OUT] | damaged-list\n";
    return 2;
  }
  output::write_binary_stl(out, mesh.vertices(), mesh.faces());
  std::cout << out << ": " << mesh.num_faces() << " faces, longest edge " << mesh.max_edge_length()
            << '\n';
  return 0;
}
