# Fails if an #include runs against the layering of the modules (docs/architecture.md):
#
#   core ← linalg, geometry, features ← bem, fem ← analysis ← apps ← python
#
# each module including only itself and the modules below it:
#   core: core            linalg: core               geometry: core
#   features: core        bem: linalg, geometry      fem: linalg, features, geometry
#   analysis: bem, fem, features, geometry, linalg   apps: everything below it
#   python (the Python module, a front end beside apps/ that shares its reports): everything
# and, inside bem/, the stages in the order the data flows:
#   kernels ← quadrature ← operators ← hmatrix ← solve ← evaluate.
# It also fails if a library module (everything below apps/) includes a command-line parser
# or writes to the terminal: they report progress through a callback and errors as
# exceptions. Usage: cmake -DSOURCE_ROOT=<project dir> -P check_layering.cmake
set(modules core linalg geometry features bem fem analysis apps python)
set(allowed_core core)
set(allowed_linalg linalg core)
set(allowed_geometry geometry core)
set(allowed_features features core)
set(allowed_bem bem linalg geometry core)
set(allowed_fem fem linalg features geometry core)
set(allowed_analysis analysis bem fem features geometry linalg core)
set(allowed_apps apps analysis bem fem features geometry linalg core)
set(allowed_python python apps analysis bem fem features geometry linalg core)
set(bem_stages kernels quadrature operators hmatrix solve evaluate)
list(JOIN bem_stages " " bem_stage_names)

set(bad "")
foreach(module IN LISTS modules)
  file(GLOB_RECURSE sources "${SOURCE_ROOT}/${module}/*.hpp" "${SOURCE_ROOT}/${module}/*.cpp")
  foreach(source IN LISTS sources)
    file(RELATIVE_PATH name "${SOURCE_ROOT}" "${source}")
    file(STRINGS "${source}" includes REGEX "^[ \t]*#[ \t]*include[ \t]*[\"<]")
    # Where a bem/ file stands in the flow of the stages (-1 outside bem/).
    set(own_stage -1)
    if(module STREQUAL "bem")
      if(name MATCHES "^bem/([a-z_]+)/")
        list(FIND bem_stages "${CMAKE_MATCH_1}" own_stage)
      endif()
      if(own_stage EQUAL -1)
        list(APPEND bad "${name}: every bem/ file belongs to a stage: ${bem_stage_names}")
      endif()
    endif()
    foreach(line IN LISTS includes)
      if(line MATCHES "#[ \t]*include[ \t]*\"([a-z_]+)/([^\"]*)\"")
        set(target "${CMAKE_MATCH_1}")
        set(rest "${CMAKE_MATCH_2}")
        list(FIND modules "${target}" known)
        if(known EQUAL -1)
          list(APPEND bad "${name}: includes \"${target}/${rest}\", outside the modules")
          continue()
        endif()
        list(FIND allowed_${module} "${target}" ok)
        if(ok EQUAL -1)
          list(APPEND bad "${name}: ${module}/ must not include \"${target}/${rest}\"")
        endif()
        if(own_stage GREATER -1 AND target STREQUAL "bem" AND rest MATCHES "^([a-z_]+)/")
          list(FIND bem_stages "${CMAKE_MATCH_1}" stage)
          if(stage GREATER own_stage)
            list(APPEND bad "${name}: a bem/ stage must not include a later one, \"bem/${rest}\"")
          endif()
        endif()
      endif()
      if(NOT module STREQUAL "apps" AND line MATCHES "<(iostream|CLI/CLI.hpp)>")
        list(APPEND bad "${name}: a library module includes ${CMAKE_MATCH_1}")
      endif()
    endforeach()
    if(NOT module STREQUAL "apps")
      file(STRINGS "${source}" prints REGEX "std::(cout|cerr|clog)|[^n]printf\\(")
      if(prints)
        list(APPEND bad "${name}: a library module writes to the terminal")
      endif()
    endif()
  endforeach()
endforeach()
if(bad)
  list(JOIN bad "\n  " text)
  message(FATAL_ERROR "includes against the layering (docs/architecture.md):\n  ${text}")
endif()
message(STATUS "layering: ${SOURCE_ROOT} ok")
