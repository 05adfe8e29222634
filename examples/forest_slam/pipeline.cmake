# forest_slam_pipeline: the monocular tree-SLAM pipeline (MonocularTreeSlam, runForestSlam)
# compiled once and linked by examples/forest_slam, examples/tree_width_study and
# bench/forest_slam.cpp. Instantiating the filter with its four models is the slowest part of
# the project's build; compiled inside each program's main.cpp it cost g++ about 5 minutes
# per program. Included from examples/forest_slam and bench (whichever comes first defines it).
if(NOT TARGET forest_slam_pipeline)
  add_library(forest_slam_pipeline STATIC
    ${CMAKE_CURRENT_LIST_DIR}/monocular_tree_slam_quaternion.cpp
    ${CMAKE_CURRENT_LIST_DIR}/monocular_tree_slam_manifold.cpp
    ${CMAKE_CURRENT_LIST_DIR}/forest_run.cpp)
  target_include_directories(forest_slam_pipeline PUBLIC ${CMAKE_CURRENT_LIST_DIR})
  target_link_libraries(forest_slam_pipeline PUBLIC sylva::sylva PRIVATE sylva_warnings)
  # The same instruction set as the programs that link it (SYLVA_NATIVE), whichever folder
  # defines it: inline functions compiled for two instruction sets in one program would be
  # merged by the linker, one copy for all.
  target_compile_options(forest_slam_pipeline PRIVATE ${SYLVA_NATIVE_OPTIONS})
endif()
