// write_analytic_outputs: writes result files of known content through the writers of
// apps/output, so that other programs (VTK's readers in test_vtk_readers.py) can check what
// they read against closed forms at realistic sizes. Prints one line per file: name, item
// counts, bytes and the seconds the writer took.
//
//   write_analytic_outputs DIR N FILE...
//
// FILE is one of
//   surface.vtp        the saddle surface below through write_vtp (the default encoding)
//   surface_ascii.vtp  the same with VtkEncoding::ascii
//   surface.ply        the same surface through write_ply, field g_1
//   grid.vti           a 3-D grid of 103×99×97 cells (1 019 200 points), point and cell data
//   image.vti          a 2-D grid of 400×300 cells (nz = 0), cell data, as `bemshape fem` on
//                      an image writes it
//
// The surface: vertices (i, j), 0 ≤ i, j ≤ N, index j·(N+1) + i, at
//   x = i/512 − 1,  y = j/512 − 1/2,  z = x·y;
// the square (i, j), 0 ≤ i, j < N, is split into the faces 2(jN + i) and 2(jN + i) + 1 with
// corners (v(i,j), v(i+1,j), v(i+1,j+1)) and (v(i,j), v(i+1,j+1), v(i,j+1)): 2N² faces,
// (N+1)² vertices, N ≤ 1024. Point fields as `bemshape thickness` names them, each value
// one correctly rounded division of an exactly representable numerator (x, y, z have at
// most 21 significant bits), so any reader computing the same formula in IEEE double gets
// the same bits and every value needs all 53 bits (Float32 would not pass):
//   g_k(x, y, z) = (k + x − 2y + 3z)/(2k + 1):  thickness = g_1, h_f = g_2, h_p = g_3,
//   f_h = g_4;  n_f = (x/3, y/5, z/7).
// Cell fields of the same names: the sum of the point values at the face's corners, added
// in corner order ((a + b) + c).
//
// The grids: point (i, j, k) at origin + spacing·(i, j, k) with origin (−1, −0.5, 0.25) and
// spacing (1/64, 1/32, 1/16) (2-D: origin (−1, −0.5, 0), spacing (1/256, 1/128, 1)), items
// x fastest, then y, then z, as VTK orders them; point field "g" = g_1 and vector "v" =
// (x/3, y/5, z/7) at the points (3-D only), cell field "g" = g_1 at the cell centres (z = 0
// in 2-D). The .vti stores Float32: the values read back are float(g).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <string>

#include <Eigen/Core>

#include "apps/output/ply_writer.hpp"
#include "apps/output/vti_writer.hpp"
#include "apps/output/vtp_writer.hpp"

using namespace bemshape;

namespace {

double g(int k, double x, double y, double z) {
  return (k + x - 2.0 * y + 3.0 * z) / (2.0 * k + 1.0);
}

struct Surface {
  Eigen::MatrixX3d vertices;
  Eigen::MatrixX3i faces;
  Eigen::MatrixXd point_fields[5], cell_fields[5];  // thickness, h_f, h_p, f_h, n_f
};

Surface saddle_surface(int n) {
  Surface s;
  const Eigen::Index nv = Eigen::Index(n + 1) * (n + 1), nf = 2 * Eigen::Index(n) * n;
  s.vertices.resize(nv, 3);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = i / 512.0 - 1.0, y = j / 512.0 - 0.5;
      s.vertices.row(Eigen::Index(j) * (n + 1) + i) << x, y, x * y;
    }
  s.faces.resize(nf, 3);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const auto v = [n](int a, int b) { return b * (n + 1) + a; };
      const Eigen::Index f = 2 * (Eigen::Index(j) * n + i);
      s.faces.row(f) << v(i, j), v(i + 1, j), v(i + 1, j + 1);
      s.faces.row(f + 1) << v(i, j), v(i + 1, j + 1), v(i, j + 1);
    }
  for (int k = 1; k <= 4; ++k) {
    Eigen::MatrixXd& p = s.point_fields[k - 1];
    p.resize(nv, 1);
    for (Eigen::Index v = 0; v < nv; ++v)
      p(v, 0) = g(k, s.vertices(v, 0), s.vertices(v, 1), s.vertices(v, 2));
  }
  Eigen::MatrixXd& n_f = s.point_fields[4];
  n_f.resize(nv, 3);
  for (Eigen::Index v = 0; v < nv; ++v)
    n_f.row(v) << s.vertices(v, 0) / 3.0, s.vertices(v, 1) / 5.0, s.vertices(v, 2) / 7.0;
  for (int field = 0; field < 5; ++field) {
    const Eigen::MatrixXd& p = s.point_fields[field];
    Eigen::MatrixXd& c = s.cell_fields[field];
    c.resize(nf, p.cols());
    for (Eigen::Index f = 0; f < nf; ++f)
      for (Eigen::Index col = 0; col < p.cols(); ++col)
        c(f, col) = p(s.faces(f, 0), col) + p(s.faces(f, 1), col) + p(s.faces(f, 2), col);
  }
  return s;
}

void write_grid(const std::string& path, bool flat) {
  output::ImageGrid grid;
  grid.cells = flat ? std::array<long long, 3>{400, 300, 0} : std::array<long long, 3>{103, 99, 97};
  grid.origin = {-1.0, -0.5, flat ? 0.0 : 0.25};
  grid.spacing = flat ? std::array<double, 3>{1 / 256.0, 1 / 128.0, 1.0}
                      : std::array<double, 3>{1 / 64.0, 1 / 32.0, 1 / 16.0};
  const long long nz = flat ? 0 : grid.cells[2];
  const auto position = [&](long long i, long long j, long long k, double shift) {
    return Eigen::Vector3d(grid.origin[0] + grid.spacing[0] * (double(i) + shift),
                           grid.origin[1] + grid.spacing[1] * (double(j) + shift),
                           flat ? 0.0 : grid.origin[2] + grid.spacing[2] * (double(k) + shift));
  };
  const long long px = grid.cells[0] + 1, py = grid.cells[1] + 1, pz = nz + 1;
  Eigen::MatrixXd point_g(px * py * pz, 1), point_v(px * py * pz, 3);
  for (long long k = 0; k < pz; ++k)
    for (long long j = 0; j < py; ++j)
      for (long long i = 0; i < px; ++i) {
        const Eigen::Vector3d p = position(i, j, k, 0.0);
        const long long at = (k * py + j) * px + i;
        point_g(at, 0) = g(1, p.x(), p.y(), p.z());
        point_v.row(at) << p.x() / 3.0, p.y() / 5.0, p.z() / 7.0;
      }
  const long long cx = grid.cells[0], cy = grid.cells[1], cz = std::max(nz, 1LL);
  Eigen::MatrixXd cell_g(cx * cy * cz, 1);
  for (long long k = 0; k < cz; ++k)
    for (long long j = 0; j < cy; ++j)
      for (long long i = 0; i < cx; ++i) {
        Eigen::Vector3d c = position(i, j, k, 0.5);
        if (flat)
          c.z() = 0.0;
        cell_g((k * cy + j) * cx + i, 0) = g(1, c.x(), c.y(), c.z());
      }
  using Location = output::ImageField::Location;
  if (flat)
    output::write_vti(path, grid, {{"g", Location::cell, &cell_g}});
  else
    output::write_vti(path, grid,
                      {{"g", Location::point, &point_g},
                       {"v", Location::point, &point_v},
                       {"g", Location::cell, &cell_g}});
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: write_analytic_outputs DIR N FILE...\n");
    return 2;
  }
  const std::filesystem::path dir = argv[1];
  const int n = std::atoi(argv[2]);
  if (n < 1 || n > 1024) {
    std::fprintf(stderr, "write_analytic_outputs: N = %s, must be 1…1024\n", argv[2]);
    return 2;
  }
  Surface surface;
  const auto timed = [&](const std::string& name, const std::function<void()>& write) {
    const auto start = std::chrono::steady_clock::now();
    write();
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("%s: %lld bytes, %.3f s\n", name.c_str(),
                static_cast<long long>(std::filesystem::file_size(dir / name)), seconds);
  };
  for (int a = 3; a < argc; ++a) {
    const std::string file = argv[a];
    const std::string path = (dir / file).string();
    const bool needs_surface = file.starts_with("surface");
    if (needs_surface && surface.faces.rows() == 0) {
      surface = saddle_surface(n);
      std::printf("surface: %lld vertices, %lld faces\n",
                  static_cast<long long>(surface.vertices.rows()),
                  static_cast<long long>(surface.faces.rows()));
    }
    const auto fields = [](const Eigen::MatrixXd* f) {
      return std::vector<output::MeshField>{
          {"thickness", &f[0]}, {"h_f", &f[1]}, {"h_p", &f[2]}, {"f_h", &f[3]}, {"n_f", &f[4]}};
    };
    if (file == "surface.vtp" || file == "surface_ascii.vtp") {
      timed(file, [&] {
        output::write_vtp(
            path, surface.vertices, surface.faces, fields(surface.point_fields),
            fields(surface.cell_fields),
            file == "surface.vtp" ? output::VtkEncoding::binary : output::VtkEncoding::ascii);
      });
    } else if (file == "surface.ply") {
      output::PlyColouring colouring;
      colouring.colour_minimum = surface.point_fields[0].minCoeff();
      colouring.colour_maximum = surface.point_fields[0].maxCoeff();
      timed(file, [&] {
        output::write_ply(path, surface.vertices, surface.faces, surface.point_fields[0].col(0),
                          colouring);
      });
    } else if (file == "grid.vti" || file == "image.vti") {
      timed(file, [&] { write_grid(path, file == "image.vti"); });
    } else {
      std::fprintf(stderr, "write_analytic_outputs: unknown file '%s'\n", file.c_str());
      return 2;
    }
  }
  return 0;
}
