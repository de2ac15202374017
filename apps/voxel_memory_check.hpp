#pragma once
// The --max-memory guards of the voxel FEM path, shared by `bemshape fem` and `bemshape
// compare`: one for the image an input file holds (checked from its header, before any
// pixel is decoded) and one for the grid the solver will run on (checked from the planned
// grid, before anything per cell is allocated). Both refuse with core/memory.hpp's
// ResourceError, which names the budget and what to do instead.

#include <cstdint>
#include <string>

#include "features/feature_parameters.hpp"
#include "fem/binary_image.hpp"
#include "fem/characteristic_function.hpp"

namespace bemshape::apps {

/// What a voxel run's memory check needs to know about the command line.
struct VoxelMemoryBudget {
  std::string input;                   ///< the input file, named in the message
  double cell = 0.0;                   ///< --cell [model units]
  bool h0_given = false;               ///< --h0 given (else h0 = kDefaultH0Cells cells)
  std::uint64_t max_memory_bytes = 0;  ///< --max-memory; 0: the machine's memory only
};

/// Refuses a planned grid whose FEM run (fem::estimated_run_bytes<D>) exceeds the budget
/// (core/memory.hpp: the machine's available memory, `ulimit -v`, --max-memory). The
/// message suggests the smallest --cell, in steps of 10 %, whose grid fits. Without --h0,
/// h0 follows the cell (kDefaultH0Cells cells) and so does the margin of 1.2·h0 around the
/// part, so below a certain budget no cell size fits; the suggestion then keeps this run's
/// h0 (--cell X --h0 H).
template <int D>
fem::GridCheck<D> voxel_grid_memory_check(const VoxelMemoryBudget& budget,
                                          const features::FeatureParameters& parameters);

/// Bytes held per pixel while an image is read: the decoded grey levels and the solid flags
/// of a PNG (2), the solid flags of a volume (1; a slice's grey levels are transient).
template <int D>
inline constexpr double kImageReadBytesPerPixel = D == 2 ? 2.0 : 1.0;

/// Refuses an image (its pixel count read from the header or --dims) whose pixels would
/// not fit the budget, suggesting a downsampled image or a larger --max-memory.
template <int D>
fem::PixelCheck image_memory_check(const VoxelMemoryBudget& budget);

}  // namespace bemshape::apps
