# bemshape_project_target(<target>): the compile settings every bemshape target shares.
# Project code builds warning-free with -Wall -Wextra -Wpedantic; third-party headers
# (Eigen, CGAL, OpenMesh, Catch2) come in through imported targets and are treated as
# system headers, so their warnings do not drown ours.
function(bemshape_project_target target)
  get_target_property(type ${target} TYPE)
  if(type STREQUAL "INTERFACE_LIBRARY")
    return()
  endif()
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic)
  if(BEMSHAPE_GCC12_AVX512)  # GCC bug 105593: false reports from its AVX-512 headers
    target_compile_options(${target} PRIVATE -Wno-maybe-uninitialized -Wno-uninitialized)
  endif()
  target_compile_features(${target} PUBLIC cxx_std_20)
endfunction()
