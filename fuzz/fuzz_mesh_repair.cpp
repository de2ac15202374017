// Fuzz harness: validation and repair (geometry::inspect_triangle_soup) on small triangle
// soups built from the bytes, without a file format in between: byte 0 gives the vertex
// count (4–35, its low five bits) and the repair length (its top three bits: 0 the default,
// 2 % of the diagonal; else 0.5·k for k = 1…7, so holes, loose pieces and self-intersecting
// regions of any size on the lattice get repaired), then one byte per coordinate on a coarse
// lattice (value/16, so coincident vertices, collinear corners, duplicate, flipped and
// intersecting faces are common), then three bytes per face (indices modulo the vertex
// count), at most 48 faces. Crossings that cannot be repaired are kept as defect regions
// (MeshPreparationOptions::measure_defects). A soup the pipeline calls usable must be closed
// and manifold, and cross itself only inside the regions it reports
// (fuzz/mesh_file_harness.hpp).
#include <algorithm>

#include "fuzz/mesh_file_harness.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace bemshape;
  if (size < 1) return 0;
  const int nv = 4 + data[0] % 32;
  geometry::MeshPreparationOptions options;
  options.repair_length = 0.5 * (data[0] / 32);
  options.measure_defects = true;
  std::size_t at = 1;
  if (size < at + 3 * static_cast<std::size_t>(nv)) return 0;
  geometry::TriangleSoup soup;
  soup.format = "fuzz";
  soup.vertices.resize(nv, 3);
  for (int v = 0; v < nv; ++v)
    for (int c = 0; c < 3; ++c) soup.vertices(v, c) = data[at++] / 16.0;
  const auto nf = static_cast<Eigen::Index>(std::min<std::size_t>((size - at) / 3, 48));
  soup.faces.resize(nf, 3);
  for (Eigen::Index f = 0; f < nf; ++f)
    for (int c = 0; c < 3; ++c) soup.faces(f, c) = data[at++] % nv;
  soup.corners_in_file = static_cast<std::size_t>(3 * nf);
  fuzz::refusal_allowed(
      [&] { fuzz::check_prepared(geometry::inspect_triangle_soup(soup, "fuzz input", options)); });
  return 0;
}
