# SPH-ASTRO - astrophysical SPH for LAMMPS. Distributed under the GNU General Public License
# version 2 (the same licence as LAMMPS); see the LICENSE file.
# SPH-ASTRO - astrophysical SPH for LAMMPS. This software is distributed under the GNU General
# Public License version 2 (the same licence as LAMMPS); see the LICENSE file.
#
# Helpers that declare the ctests of unittest/CMakeLists.txt. Every test carries one or more
# of the labels
#   unit    pure C++ units and the Python reference solvers, no LAMMPS (seconds: the inner loop)
#   long    a minute or more each (a second plugin build, a long MSM run): run by tools/test.sh
#           --all and CI, left out of tools/test.sh
#   lammps  GoogleTest executables that drive LAMMPS through its C++ library interface
#   scene   short scenes run with lmp or Python and analysed, with asserted bounds
#   mpi     runs on several MPI ranks (the MPI equivalence tests)
# and writes whatever it writes under ${CMAKE_BINARY_DIR}/test_output/<test name>.
#
# Needs SPH_ASTRO_ROOT, SPH_ASTRO_PYTHON and SPH_ASTRO_ENV (cmake/CMakeLists.txt).

set(SPH_ASTRO_TEST_OUTPUT ${CMAKE_BINARY_DIR}/test_output)

# sph_astro_add_gtest(<name> [LAMMPS] [INCLUDE <dir>...])
#
# Builds test_<name> from test_<name>.cpp and registers it as the test <name>. Without LAMMPS:
# a pure unit (sph_astro_core, GoogleTest's main), label unit. With LAMMPS: linked to
# liblammps with lammps_test_main.cpp (MPI around the tests), SPH_ASTRO_PLUGIN is the plugin's path (the tests load it themselves, so the test
# gets no LAMMPS_PLUGIN_PATH), run in the build's unittest directory, label lammps.
function(sph_astro_add_gtest name)
  cmake_parse_arguments(PARSE_ARGV 1 T "LAMMPS" "" "INCLUDE")
  if(T_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "sph_astro_add_gtest(${name}): unknown arguments ${T_UNPARSED_ARGUMENTS}")
  endif()
  add_executable(test_${name} ${CMAKE_CURRENT_SOURCE_DIR}/test_${name}.cpp)
  if(T_INCLUDE)
    target_include_directories(test_${name} PRIVATE ${T_INCLUDE})
  endif()
  # (the package's code generation: a test that compiles a package source sees its numbers)
  target_link_libraries(test_${name} PRIVATE sph_astro_codegen)
  add_test(NAME ${name} COMMAND test_${name})
  if(T_LAMMPS)
    target_sources(test_${name} PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/lammps_test_main.cpp)
    target_link_libraries(test_${name} PRIVATE lammps_headers lammps_shared GTest::gtest)
    target_compile_definitions(test_${name} PRIVATE
      SPH_ASTRO_PLUGIN="${CMAKE_BINARY_DIR}/plugins/sphastroplugin.so")
    add_dependencies(test_${name} sphastroplugin)
    set_tests_properties(${name} PROPERTIES WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}
                                            LABELS lammps)
  else()
    target_link_libraries(test_${name} PRIVATE sph_astro_core GTest::gtest_main)
    set_tests_properties(${name} PROPERTIES LABELS unit)
  endif()
endfunction()

# sph_astro_add_python_test(NAME <name> LABELS <label>... ARGS <argument>...)
#
# Runs ${SPH_ASTRO_PYTHON} <argument>... (build/venv's Python, with the sphastro package) in the
# SPH-ASTRO environment (lmp, liblammps, LAMMPS' Python module, the plugin path). The scripts
# take their output directory as an argument: by convention ${SPH_ASTRO_TEST_OUTPUT}/<name>.
function(sph_astro_add_python_test)
  cmake_parse_arguments(PARSE_ARGV 0 T "" "NAME" "LABELS;ARGS")
  if(NOT T_NAME OR NOT T_LABELS OR NOT T_ARGS OR T_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "sph_astro_add_python_test: NAME, LABELS and ARGS needed "
                        "(unknown: ${T_UNPARSED_ARGUMENTS})")
  endif()
  add_test(NAME ${T_NAME} COMMAND ${SPH_ASTRO_PYTHON} ${T_ARGS})
  set_tests_properties(${T_NAME} PROPERTIES ENVIRONMENT "${SPH_ASTRO_ENV}" LABELS "${T_LABELS}")
endfunction()

# add_scene_test(NAME <name> SCENE <folder under examples/>
#                [INPUT <in.file>]            input in the scene folder (default in.<SCENE>)
#                [RANKS <n>]                  1 (default): lmp itself; n > 1: mpirun -np n, and
#                                             the test also gets the label mpi
#                [VARS <name> <value>...]     passed to lmp as -var <name> <value>
#                [ANALYSE <script>]           in the scene folder (default analyse.py)
#                [ANALYSE_ARGS <argument>...] the analysis script's arguments (dump, --log, ...)
#                [ASSERT <bounds>]            appended as --assert <bounds>
#                [FILES <file>...]            copied from the scene folder into the working
#                                             directory before the run
#                [LABELS <label>...]          further labels
#                [LAUNCHER <command>...])     runs the driver through <command> (e.g. the
#                                             in-tree lmp: tools/lammps_in_tree.sh --run)
#
# In ${SPH_ASTRO_TEST_OUTPUT}/<name> (created by the driver unittest/run_scene.sh):
#   [mpirun -np n] lmp -in examples/<SCENE>/<INPUT> -log log.lammps -screen none -var ...
#   ${SPH_ASTRO_PYTHON} examples/<SCENE>/<ANALYSE> <ANALYSE_ARGS> [--assert <bounds>]
# The test fails when either fails. Label scene, environment ${SPH_ASTRO_ENV}.
function(add_scene_test)
  cmake_parse_arguments(PARSE_ARGV 0 T "" "NAME;SCENE;INPUT;RANKS;ANALYSE;ASSERT"
                        "VARS;ANALYSE_ARGS;FILES;LABELS;LAUNCHER")
  if(NOT T_NAME OR NOT T_SCENE OR T_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "add_scene_test: NAME and SCENE needed (unknown: ${T_UNPARSED_ARGUMENTS})")
  endif()
  set(scene_dir ${SPH_ASTRO_ROOT}/examples/${T_SCENE})
  if(NOT T_INPUT)
    get_filename_component(T_INPUT ${T_SCENE} NAME)
    set(T_INPUT in.${T_INPUT})
  endif()
  if(NOT T_RANKS)
    set(T_RANKS 1)
  endif()
  if(NOT T_ANALYSE)
    set(T_ANALYSE analyse.py)
  endif()
  foreach(f ${scene_dir}/${T_INPUT} ${scene_dir}/${T_ANALYSE})
    if(NOT EXISTS ${f})
      message(FATAL_ERROR "add_scene_test(${T_NAME}): ${f} not found")
    endif()
  endforeach()
  list(LENGTH T_VARS nvars)
  math(EXPR odd "${nvars} % 2")
  if(odd)
    message(FATAL_ERROR "add_scene_test(${T_NAME}): VARS takes name value pairs: ${T_VARS}")
  endif()
  set(cmd ${T_LAUNCHER} ${SPH_ASTRO_ROOT}/unittest/run_scene.sh
          ${SPH_ASTRO_TEST_OUTPUT}/${T_NAME} ${T_RANKS} ${scene_dir}/${T_INPUT})
  foreach(f ${T_FILES})
    list(APPEND cmd --copy ${scene_dir}/${f})
  endforeach()
  while(T_VARS)
    list(POP_FRONT T_VARS var value)
    list(APPEND cmd -var ${var} ${value})
  endwhile()
  list(APPEND cmd --analyse ${scene_dir}/${T_ANALYSE} ${T_ANALYSE_ARGS})
  if(T_ASSERT)
    list(APPEND cmd --assert ${T_ASSERT})
  endif()
  set(labels scene ${T_LABELS})
  if(T_RANKS GREATER 1)
    list(APPEND labels mpi)
  endif()
  list(REMOVE_DUPLICATES labels)
  add_test(NAME ${T_NAME} COMMAND ${cmd})
  set_tests_properties(${T_NAME} PROPERTIES ENVIRONMENT "${SPH_ASTRO_ENV}" LABELS "${labels}"
                                            PROCESSORS ${T_RANKS})
endfunction()
