# Helpers that give every project target the same flags.
# Generated code (idl/) is compiled without -Werror: its warnings are not ours to fix.

set(WBI_WARNINGS -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wold-style-cast
                 -Wcast-align -Woverloaded-virtual -Werror)

# wbi_add_library(NAME <target> [SHARED|STATIC] SOURCES ... [PUBLIC_DEPS ...] [PRIVATE_DEPS ...])
# Creates wbi_<name> with alias wbi::<name>; headers in <dir>/include are public.
function(wbi_add_library)
  cmake_parse_arguments(ARG "" "NAME" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  set(target wbi_${ARG_NAME})
  add_library(${target} ${ARG_SOURCES})
  add_library(wbi::${ARG_NAME} ALIAS ${target})
  set_target_properties(${target} PROPERTIES OUTPUT_NAME wbi_${ARG_NAME} EXPORT_NAME ${ARG_NAME})
  target_include_directories(${target} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(${target} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  target_compile_options(${target} PRIVATE ${WBI_WARNINGS})
  get_target_property(type ${target} TYPE)
  if(type STREQUAL "SHARED_LIBRARY" AND NOT WBI_SANITIZE)
    # Every symbol it uses is in its declared dependencies: a plugin that
    # loads it then finds them (the sanitizers' runtime is the program's).
    target_link_options(${target} PRIVATE -Wl,--no-undefined)
  endif()
  set_property(GLOBAL APPEND PROPERTY WBI_INSTALLED_TARGETS ${target})
  if(EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/include)
    install(DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  endif()
endfunction()

# wbi_add_header_library(NAME <name> [INCLUDE_DIR <dir>] [DEPS ...])
# A header-only library wbi_<name> (alias wbi::<name>): its headers in
# INCLUDE_DIR (default <dir>/include), installed.
function(wbi_add_header_library)
  cmake_parse_arguments(ARG "" "NAME;INCLUDE_DIR" "DEPS" ${ARGN})
  if(NOT ARG_INCLUDE_DIR)
    set(ARG_INCLUDE_DIR ${CMAKE_CURRENT_SOURCE_DIR}/include)
  endif()
  set(target wbi_${ARG_NAME})
  add_library(${target} INTERFACE)
  add_library(wbi::${ARG_NAME} ALIAS ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${ARG_NAME})
  target_include_directories(${target} INTERFACE
    $<BUILD_INTERFACE:${ARG_INCLUDE_DIR}>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(${target} INTERFACE ${ARG_DEPS})
  set_property(GLOBAL APPEND PROPERTY WBI_INSTALLED_TARGETS ${target})
  install(DIRECTORY ${ARG_INCLUDE_DIR}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endfunction()

# wbi_add_subfolders(): every sub-folder of the current folder that has a
# CMakeLists.txt, in name order, unless WBI_SKIP_AREAS names it (as `name` or
# `<folder>/name`). The layer folders (robot_side/, components/, tools/,
# testing/) are lists of such sub-folders.
function(wbi_add_subfolders)
  file(RELATIVE_PATH area ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_SOURCE_DIR})
  file(GLOB dirs LIST_DIRECTORIES true CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*)
  foreach(dir ${dirs})
    if(IS_DIRECTORY ${dir} AND EXISTS ${dir}/CMakeLists.txt)
      get_filename_component(name ${dir} NAME)
      if(NOT name IN_LIST WBI_SKIP_AREAS AND NOT "${area}/${name}" IN_LIST WBI_SKIP_AREAS)
        add_subdirectory(${name})
      endif()
    endif()
  endforeach()
endfunction()

# wbi_add_executable(NAME <exe> SOURCES ... [DEPS ...] [NO_INSTALL])
function(wbi_add_executable)
  cmake_parse_arguments(ARG "NO_INSTALL" "NAME" "SOURCES;DEPS" ${ARGN})
  add_executable(${ARG_NAME} ${ARG_SOURCES})
  target_link_libraries(${ARG_NAME} PRIVATE ${ARG_DEPS})
  target_compile_options(${ARG_NAME} PRIVATE ${WBI_WARNINGS})
  if(NOT ARG_NO_INSTALL)
    install(TARGETS ${ARG_NAME} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  endif()
endfunction()

# Tests labelled "sanitize" (parsing and DDS) are rebuilt and rerun under
# ASan/UBSan by scripts/test: `cmake --build B --target wbi_sanitize_targets`
# builds exactly them and the helper programs they start (wbi_sanitize_also).
add_custom_target(wbi_sanitize_targets)
function(wbi_sanitize_also)
  add_dependencies(wbi_sanitize_targets ${ARGN})
endfunction()

# Each test gets its own DDS domain id in WBI_DOMAIN_ID (WBI_TEST_DOMAIN_FIRST,
# +1, ... up to 231, dds::kMaxDomainId), so that tests running in parallel
# never discover each other. Two build trees whose tests run at the same time on one machine need
# different WBI_TEST_DOMAIN_FIRST values (discovery is loopback-wide).
set(WBI_TEST_DOMAIN_FIRST 1 CACHE STRING "DDS domain id of the first test (the others follow)")
set_property(GLOBAL PROPERTY WBI_NEXT_TEST_DOMAIN ${WBI_TEST_DOMAIN_FIRST})

# wbi_next_test_domain(<out-var>): takes the next free test domain id.
function(wbi_next_test_domain out)
  get_property(domain GLOBAL PROPERTY WBI_NEXT_TEST_DOMAIN)
  if(domain GREATER 231)
    message(FATAL_ERROR "DDS domain ids for tests are used up (the last is 231): "
      "lower WBI_TEST_DOMAIN_FIRST (${WBI_TEST_DOMAIN_FIRST})")
  endif()
  math(EXPR next "${domain} + 1")
  set_property(GLOBAL PROPERTY WBI_NEXT_TEST_DOMAIN ${next})
  set(${out} ${domain} PARENT_SCOPE)
endfunction()

# A test that ran nothing says so in one line that begins with "skipped: "
# (tests/README.md, "Skipped tests"): a script prints it (and exits 77), a
# GoogleTest program prints it when every test it ran was skipped and none
# failed (tests/support/skip_report.cpp). ctest then reports the test as
# skipped, not passed. A program of which only some tests skipped stays
# passed (or failed): GoogleTest's own "[  SKIPPED ]" lines are not matched,
# since a match would make ctest report "Skipped" even for a program whose
# other tests failed. scripts/test lists both kinds and fails on any.
set(WBI_TEST_SKIP_REGEX "(^|\n)skipped: ")

# wbi_test_skips(<test>...): ctest reports these tests as skipped when they print that line.
function(wbi_test_skips)
  set_tests_properties(${ARGN} PROPERTIES SKIP_REGULAR_EXPRESSION "${WBI_TEST_SKIP_REGEX}")
endfunction()

# wbi_add_test(NAME <test> SOURCES ... [DEPS ...] [LABELS ...] [TIMEOUT s])
# One GoogleTest executable, registered with ctest as one test (its cases run in one process).
function(wbi_add_test)
  cmake_parse_arguments(ARG "" "NAME;TIMEOUT" "SOURCES;DEPS;LABELS" ${ARGN})
  add_executable(${ARG_NAME} ${ARG_SOURCES})
  target_link_libraries(${ARG_NAME} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gtest_main
    wbi_test_crash_backtrace wbi_test_skip_report)
  target_compile_options(${ARG_NAME} PRIVATE ${WBI_WARNINGS})
  set_target_properties(${ARG_NAME} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/tests)
  add_test(NAME ${ARG_NAME} COMMAND ${ARG_NAME})
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 120)
  endif()
  wbi_next_test_domain(domain)
  if("sanitize" IN_LIST ARG_LABELS)
    add_dependencies(wbi_sanitize_targets ${ARG_NAME})
  endif()
  set_tests_properties(${ARG_NAME} PROPERTIES TIMEOUT ${ARG_TIMEOUT}
    LABELS "${ARG_LABELS}"
    ENVIRONMENT "WBI_SOURCE_DIR=${PROJECT_SOURCE_DIR};WBI_BINARY_DIR=${PROJECT_BINARY_DIR};WBI_DOMAIN_ID=${domain}")
  wbi_test_skips(${ARG_NAME})
endfunction()

# wbi_test_no_malloc(<test>): Eigen fails the test on any heap allocation
# (EIGEN_RUNTIME_NO_MALLOC, checked by eigen_assert, so asserts stay on in
# every build type).
function(wbi_test_no_malloc target)
  target_compile_definitions(${target} PRIVATE EIGEN_RUNTIME_NO_MALLOC)
  target_compile_options(${target} PRIVATE -UNDEBUG)
endfunction()
