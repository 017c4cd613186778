# SPH-ASTRO package of LAMMPS: cmake/Modules/Packages/SPH-ASTRO.cmake of a LAMMPS tree
# (tools/lammps_in_tree.sh puts it there; src/SPH-ASTRO/README). The package writes snapshots
# through the C API of HDF5; it uses the serial interface, as the H5MD package does.
enable_language(C)
set(HDF5_PREFER_PARALLEL FALSE)
find_package(HDF5 REQUIRED COMPONENTS C)
# parallel HDF5 brings MPI headers that conflict with a serial (STUBS) LAMMPS build
if((NOT BUILD_MPI) AND HDF5_IS_PARALLEL)
  message(FATAL_ERROR "Serial LAMMPS build and parallel HDF5 library are not compatible")
endif()
target_link_libraries(lammps PRIVATE ${HDF5_C_LIBRARIES})
target_include_directories(lammps PRIVATE ${HDF5_C_INCLUDE_DIRS})
if(HDF5_C_DEFINITIONS)
  target_compile_definitions(lammps PRIVATE ${HDF5_C_DEFINITIONS})
endif()
# the package's sources without FMA contraction, whatever instruction set this LAMMPS build
# targets: every product and sum rounded on its own, the numbers of the plugin's build
# (cmake/CMakeLists.txt) bit for bit
include(CheckCXXCompilerFlag)
check_cxx_compiler_flag(-ffp-contract=off SPH_ASTRO_HAS_FP_CONTRACT_OFF)
if(SPH_ASTRO_HAS_FP_CONTRACT_OFF)
  file(GLOB _sph_astro_sources ${LAMMPS_SOURCE_DIR}/SPH-ASTRO/*.cpp)
  set_source_files_properties(${_sph_astro_sources} PROPERTIES COMPILE_OPTIONS -ffp-contract=off)
endif()
