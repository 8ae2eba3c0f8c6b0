# One library target per subsystem folder, with the subsystems it may use (docs/layout.md).
#
#   windplan_subsystem(geometry_mesh DIR geometry/mesh USES geometry_base SOURCES mesh.cpp ...)
#
# creates the static library windplan_<name> (alias windplan::<name>) from the folder's sources,
# links the USES targets publicly, and records the folder and what it may use. The layer check
# (cmake/check_layers.cmake, run by every build and by ctest) reads that record: a source in a
# folder may include headers of its own folder and of the folders its USES reach, nothing else.
# So the link graph and the include rule are one table, written once, here in the CMakeLists.
function(windplan_subsystem name)
  cmake_parse_arguments(ARG "" "DIR" "USES;SOURCES" ${ARGN})
  if(ARG_SOURCES)
    add_library(windplan_${name} STATIC ${ARG_SOURCES})
    set(scope PUBLIC)
    target_compile_options(windplan_${name} PRIVATE ${WINDPLAN_WARNINGS})
  else()  # headers only (planner/plan)
    add_library(windplan_${name} INTERFACE)
    set(scope INTERFACE)
  endif()
  add_library(windplan::${name} ALIAS windplan_${name})
  target_include_directories(windplan_${name} ${scope} ${PROJECT_SOURCE_DIR}
                                                       ${CMAKE_BINARY_DIR}/generated)
  target_link_libraries(windplan_${name} ${scope} Eigen3::Eigen)
  foreach(u ${ARG_USES})
    target_link_libraries(windplan_${name} ${scope} windplan_${u})
  endforeach()
  add_dependencies(windplan_${name} windplan_layer_check)
  windplan_layer(${name} DIR ${ARG_DIR} USES ${ARG_USES})
endfunction()

# Records a layer (a folder and the layers it may use) without creating a library: the CLI and
# the benchmarks. ALSO names folders that are no layer but that this one may include (the
# benchmarks' use of the tests' plan fixtures).
function(windplan_layer name)
  cmake_parse_arguments(ARG "" "DIR" "USES;ALSO" ${ARGN})
  set_property(GLOBAL APPEND PROPERTY WINDPLAN_LAYERS ${name})
  set_property(GLOBAL PROPERTY WINDPLAN_LAYER_DIR_${name} ${ARG_DIR})
  set_property(GLOBAL PROPERTY WINDPLAN_LAYER_USES_${name} ${ARG_USES})
  set_property(GLOBAL PROPERTY WINDPLAN_LAYER_ALSO_${name} ${ARG_ALSO})
endfunction()

# Writes the rules file: one line per layer, "<dir>|<allowed dir>;<allowed dir>..." with the
# allowed folders the transitive closure of USES (plus the folder itself).
function(windplan_write_layer_rules file)
  get_property(layers GLOBAL PROPERTY WINDPLAN_LAYERS)
  set(text "")
  foreach(l ${layers})
    set(seen "")
    set(todo ${l})
    while(todo)
      list(POP_FRONT todo cur)
      if(cur IN_LIST seen)
        continue()
      endif()
      list(APPEND seen ${cur})
      get_property(u GLOBAL PROPERTY WINDPLAN_LAYER_USES_${cur})
      foreach(x ${u})
        get_property(known GLOBAL PROPERTY WINDPLAN_LAYER_DIR_${x} SET)
        if(NOT known)
          message(FATAL_ERROR "layer ${cur} uses ${x}, which is not a layer")
        endif()
      endforeach()
      list(APPEND todo ${u})
    endwhile()
    set(dirs "")
    foreach(s ${seen})
      get_property(d GLOBAL PROPERTY WINDPLAN_LAYER_DIR_${s})
      list(APPEND dirs ${d})
    endforeach()
    get_property(also GLOBAL PROPERTY WINDPLAN_LAYER_ALSO_${l})
    list(APPEND dirs ${also})
    get_property(own GLOBAL PROPERTY WINDPLAN_LAYER_DIR_${l})
    string(APPEND text "${own}|${dirs}\n")
  endforeach()
  file(WRITE ${file} "${text}")
endfunction()
