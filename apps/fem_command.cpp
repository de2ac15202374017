#include "apps/fem_command.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "analysis/memory_budget.hpp"
#include "analysis/voxel_resolution.hpp"
#include "apps/exit_codes.hpp"
#include "apps/output/png_writer.hpp"
#include "apps/output/vti_writer.hpp"
#include "apps/run_limits.hpp"
#include "core/errors.hpp"
#include "fem/binary_image.hpp"
#include "fem/characteristic_function.hpp"
#include "fem/shape_feature_solver.hpp"
#include "fem/voxel_features.hpp"
#include "geometry/mesh_preparation.hpp"

namespace bemshape::apps {
namespace {

namespace fs = std::filesystem;
using analysis::image_memory_check;
using analysis::kDefaultH0Cells;
using analysis::kMaxResolvedKappaCell;
using analysis::voxel_grid_memory_check;
using analysis::VoxelMemoryBudget;

struct FemOptions {
  std::string input, output;
  double cell = 0.0, h0 = 0.0, a = 0.2, pixel = 1.0;
  bool invert = false;
  std::vector<long long> dims;
  int samples = 1;
  std::uint64_t max_memory_bytes = 0;  // --max-memory; 0: the machine's memory only
};

ProgressCallback stderr_progress() {
  auto last = std::make_shared<std::pair<std::string, int>>("", -1);
  return [last](std::string_view stage, double fraction) {
    const int percent = static_cast<int>(std::floor(fraction * 10.0)) * 10;
    if (last->first == stage && last->second == percent)
      return;
    *last = {std::string(stage), percent};
    std::cerr << "bemshape fem: " << stage << ' ' << percent << "%\n";
  };
}

template <int D>
output::ImageGrid image_grid(const fem::VoxelGrid<D>& grid) {
  output::ImageGrid g;
  for (int d = 0; d < D; ++d) {
    g.cells[d] = grid.cells[d];
    g.origin[d] = grid.origin(d);
    g.spacing[d] = grid.cell_size;
  }
  return g;
}

void write_pictures(const fs::path& base, const fem::VoxelGrid<2>& grid,
                    const fem::VoxelFeatures<2>& f, const features::FeatureParameters& p) {
  const int nx = static_cast<int>(grid.cells[0]), ny = static_cast<int>(grid.cells[1]);
  std::vector<char> solid(grid.chi.size());
  for (std::size_t e = 0; e < solid.size(); ++e)
    solid[e] = grid.chi[e] >= fem::kSolidFraction;
  const int k = std::max(1, 1200 / std::max(nx, ny));
  const auto stem = base.parent_path() / base.stem();
  const auto field_picture = [&](const char* name, const Eigen::VectorXd& v) {
    double lo = 1e300, hi = -1e300;
    for (Eigen::Index e = 0; e < v.size(); ++e)
      if (solid[static_cast<std::size_t>(e)]) {
        lo = std::min(lo, v[e]);
        hi = std::max(hi, v[e]);
      }
    output::FieldPictureOptions options;
    options.minimum = lo;
    options.maximum = hi;
    options.pixels_per_cell = k;
    output::paint_scalar_field(v, nx, ny, solid, options)
        .write_png(stem.string() + "_" + name + ".png");
  };
  field_picture("f_h", f.field.f_h);
  // h_f saturates where f_h vanishes (corners); show it up to 3·h0 like the paper's scale.
  field_picture("h_f", f.field.h_f.cwiseMin(3.0 * p.h0));
  // Skeleton: grey solid, black skeleton cells.
  {
    output::RgbImage canvas(nx * k, ny * k);
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const auto e = static_cast<std::size_t>(j) * nx + i;
        const output::Rgb c = f.field.skeleton[e] ? output::Rgb{0, 0, 0}
                              : solid[e]          ? output::Rgb{190, 190, 190}
                                                  : output::Rgb{255, 255, 255};
        canvas.fill_rectangle(i * k, (ny - 1 - j) * k, (i + 1) * k, (ny - j) * k, c);
      }
    canvas.write_png(stem.string() + "_skeleton.png");
  }
  // Orientation: n_f (blue) and t_f (red) glyphs on a grid of cells over the grey solid.
  {
    output::RgbImage canvas(nx * k, ny * k);
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        if (solid[static_cast<std::size_t>(j) * nx + i])
          canvas.fill_rectangle(i * k, (ny - 1 - j) * k, (i + 1) * k, (ny - j) * k,
                                {210, 210, 210});
    const int step = std::max(2, std::max(nx, ny) / 60), length = step * k * 2 / 5;
    for (int j = step / 2; j < ny; j += step)
      for (int i = step / 2; i < nx; i += step) {
        const auto e = static_cast<Eigen::Index>(j) * nx + i;
        if (!solid[static_cast<std::size_t>(e)])
          continue;
        const int cx = i * k + k / 2, cy = (ny - 1 - j) * k + k / 2;
        const Eigen::Vector2d n = f.field.n_f.row(e).transpose(),
                              t = f.field.t_f.row(e).transpose();
        canvas.draw_line(cx, cy, cx + static_cast<int>(length * n.x()),
                         cy - static_cast<int>(length * n.y()), {30, 60, 220});
        canvas.draw_line(cx, cy, cx + static_cast<int>(length * t.x()),
                         cy - static_cast<int>(length * t.y()), {220, 40, 40});
      }
    canvas.write_png(stem.string() + "_orientation.png");
  }
}

template <int D>
void solve_and_write(const fem::VoxelGrid<D>& grid, const features::FeatureParameters& p,
                     const fs::path& out) {
  const double kappa_cell = p.kappa() * grid.cell_size;
  if (kappa_cell > kMaxResolvedKappaCell)
    std::cerr << "bemshape fem: note: kappa*cell = " << kappa_cell
              << " > 0.5: the boundary layer of s is under-resolved, expect thickness errors of "
                 "several %; use --cell "
              << kMaxResolvedKappaCell / p.kappa() << " or smaller, or a larger --h0\n";
  const auto progress = stderr_progress();
  const auto solution = fem::solve_shape_feature_pde<D>(grid, p, {}, progress);
  const auto f = fem::voxel_features<D>(grid, solution.s, p);

  Eigen::MatrixXd chi(grid.num_cells(), 1), skeleton(grid.num_cells(), 1);
  for (Eigen::Index e = 0; e < chi.rows(); ++e) {
    chi(e, 0) = grid.chi[static_cast<std::size_t>(e)];
    skeleton(e, 0) = f.field.skeleton[static_cast<std::size_t>(e)];
  }
  const Eigen::MatrixXd f_h = f.field.f_h, h_f = f.field.h_f, h_p = f.field.h_p;
  using Location = output::ImageField::Location;
  output::write_vti(out, image_grid<D>(grid),
                    {{"chi", Location::cell, &chi},
                     {"s", Location::cell, &f.s},
                     {"f_h", Location::cell, &f_h},
                     {"h_f", Location::cell, &h_f},
                     {"h_p", Location::cell, &h_p},
                     {"n_f", Location::cell, &f.field.n_f},
                     {"skeleton", Location::cell, &skeleton}});
  if constexpr (D == 2)
    write_pictures(out, grid, f, p);

  std::vector<double> thickness;
  for (Eigen::Index e = 0; e < chi.rows(); ++e)
    if (chi(e, 0) >= fem::kSolidFraction)
      thickness.push_back(h_p(e, 0));
  std::sort(thickness.begin(), thickness.end());
  std::cout << "bemshape fem: " << D << "-D grid";
  for (int d = 0; d < D; ++d)
    std::cout << (d ? " x " : " ") << grid.cells[d];
  std::cout << " cells of " << grid.cell_size << ", h0 = " << p.h0 << ", a = " << p.a << '\n'
            << "  solver           " << solution.report.iterations << " CG iterations, "
            << solution.report.multigrid_levels << " multigrid levels, "
            << solution.report.setup_seconds + solution.report.solve_seconds << " s\n";
  if (!thickness.empty())
    std::cout << "  thickness h_p    min " << thickness.front() << ", median "
              << thickness[thickness.size() / 2] << " over " << thickness.size()
              << " solid cells\n";
  std::cout << "  written          " << out.string()
            << (D == 2 ? " (+ _f_h, _h_f, _skeleton, _orientation .png)" : "") << '\n';
}

void run(const FemOptions& o) {
  const fs::path input(o.input);
  fs::path out =
      o.output.empty() ? fs::path(input.stem().string() + "_fem.vti") : fs::path(o.output);
  features::FeatureParameters p;
  p.a = o.a;
  p.h0 = o.h0 > 0.0 ? o.h0 : kDefaultH0Cells * o.cell;
  features::validate(p);
  if (!(o.cell > 0.0))
    throw InputError("--cell must be a positive length");
  const VoxelMemoryBudget budget{o.input, o.cell, o.h0 > 0.0, o.max_memory_bytes};
  std::string ext = input.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (fs::is_directory(input) || !o.dims.empty()) {
    fem::BinaryImage<3> volume;
    if (fs::is_directory(input)) {
      volume = fem::read_png_stack(input, o.invert, image_memory_check<3>(budget));
    } else {
      if (o.dims.size() != 3)
        throw InputError("--dims needs three numbers NX,NY,NZ");
      volume = fem::read_raw_volume(input, {o.dims[0], o.dims[1], o.dims[2]}, o.invert,
                                    image_memory_check<3>(budget));
    }
    solve_and_write<3>(
        fem::grid_for_image<3>(volume, o.pixel, o.cell, p, o.samples, fem::kDefaultMaxCells<3>,
                               voxel_grid_memory_check<3>(budget, p)),
        p, out);
  } else if (ext == ".png") {
    const auto image = fem::read_png_image(input, o.invert, image_memory_check<2>(budget));
    solve_and_write<2>(
        fem::grid_for_image<2>(image, o.pixel, o.cell, p, o.samples, fem::kDefaultMaxCells<2>,
                               voxel_grid_memory_check<2>(budget, p)),
        p, out);
  } else {
    const auto prepared = geometry::prepare_mesh_file(input);
    solve_and_write<3>(
        fem::grid_for_mesh(prepared.mesh, o.cell, p, o.samples, fem::kDefaultMaxCells<3>,
                           voxel_grid_memory_check<3>(budget, p)),
        p, out);
  }
}

}  // namespace

void register_fem_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<FemOptions>();
  CLI::App* cmd = app.add_subcommand(
      "fem",
      "Voxel finite-element solve of the shape-feature PDE on an image (PNG, PNG-slice folder, "
      "raw bytes with --dims) or a voxelised surface mesh; writes a .vti (and PNG pictures in "
      "2-D)");
  cmd->add_option("INPUT", options->input,
                  "PNG image, folder of PNG slices, raw volume or mesh file (.stl, .obj, .off, "
                  ".ply, .3mf)")
      ->required();
  cmd->add_option("--cell", options->cell, "grid cell size [model units]")->required();
  cmd->add_option(
      "--h0", options->h0,
      "characteristic length h0 (about the smallest thickness of interest); default 20 cells");
  cmd->add_option("--a", options->a, "dimensionless diffusion parameter a")->capture_default_str();
  cmd->add_flag("--invert", options->invert, "light pixels / zero bytes are solid");
  cmd->add_option("--pixel", options->pixel, "pixel (voxel) size of image input [model units]")
      ->capture_default_str();
  cmd->add_option("--dims", options->dims, "raw volume dimensions NX,NY,NZ")->delimiter(',');
  cmd->add_option(
         "--samples", options->samples,
         "inside tests per cell and axis (1: centre test, binary chi; K > 1: volume fraction)")
      ->capture_default_str();
  cmd->add_option("-o,--output", options->output, "output .vti path (default INPUT-stem_fem.vti)");
  add_timeout_option(*cmd);
  add_max_memory_option(*cmd, options->max_memory_bytes);
  cmd->callback([options, &exit_code]() {
    run(*options);
    exit_code = kExitSuccess;
  });
}

}  // namespace bemshape::apps
