# Build helpers shared by every Lantern target: language level, warnings, sanitizers,
# and the lantern_module / lantern_executable / lantern_test functions.
include_guard(GLOBAL)

set(CMAKE_EXPORT_COMPILE_COMMANDS ON)
if(NOT CMAKE_BUILD_TYPE AND NOT CMAKE_CONFIGURATION_TYPES)
    set(CMAKE_BUILD_TYPE RelWithDebInfo CACHE STRING "Build type" FORCE)
endif()

find_package(Threads REQUIRED)
include(GNUInstallDirs)

# What every Lantern library asks of its users (PUBLIC): C++20, and whether LANTERN_ASSERT is
# compiled in (the public headers' inline code must agree with the libraries). Installed.
add_library(lantern_public_options INTERFACE)
add_library(lantern::public_options ALIAS lantern_public_options)
target_compile_features(lantern_public_options INTERFACE cxx_std_20)
if(LANTERN_ASSERTS)
    target_compile_definitions(lantern_public_options INTERFACE LANTERN_ENABLE_ASSERTS=1)
endif()

# How Lantern itself is built (PRIVATE to its libraries, so never a user's: warnings,
# -Werror, sanitizers). One interface target carries every flag, so options are configured
# through targets only. Executables and tests in the tree link it directly.
add_library(lantern_build_options INTERFACE)
add_library(lantern::build_options ALIAS lantern_build_options)
target_link_libraries(lantern_build_options INTERFACE lantern_public_options)
target_compile_options(lantern_build_options INTERFACE
    $<$<COMPILE_LANGUAGE:CXX>:-Wall -Wextra -Wshadow>
    $<$<BOOL:${LANTERN_WERROR}>:-Werror>)

if(LANTERN_SANITIZE STREQUAL "address")
    # float-cast-overflow: a float converted to an int that cannot hold it (not in
    # -fsanitize=undefined by default).
    set(_lantern_san -fsanitize=address,undefined,float-cast-overflow -fno-sanitize-recover=undefined,float-cast-overflow
                     -fno-omit-frame-pointer)
    if(CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
        # The clang build is also the fuzzing build: everything carries libFuzzer's coverage
        # instrumentation, and tests/fuzz links its targets with -fsanitize=fuzzer.
        list(APPEND _lantern_san -fsanitize=fuzzer-no-link)
    endif()
elseif(LANTERN_SANITIZE STREQUAL "undefined")
    set(_lantern_san -fsanitize=undefined,float-cast-overflow -fno-sanitize-recover=undefined,float-cast-overflow
                     -fno-omit-frame-pointer)
elseif(LANTERN_SANITIZE STREQUAL "thread")
    set(_lantern_san -fsanitize=thread -fno-omit-frame-pointer)
elseif(NOT LANTERN_SANITIZE STREQUAL "")
    message(FATAL_ERROR "LANTERN_SANITIZE must be address, undefined, thread or empty (got '${LANTERN_SANITIZE}')")
endif()
if(_lantern_san)
    target_compile_options(lantern_build_options INTERFACE ${_lantern_san})
    target_link_options(lantern_build_options INTERFACE ${_lantern_san})
    target_compile_definitions(lantern_build_options INTERFACE LANTERN_SANITIZER_BUILD=1)
endif()

# lantern_module(<name> [SOURCES ...] [PUBLIC_DEPS ...] [PRIVATE_DEPS ...])
# Creates the static library lantern_<name> with the alias engine::<name>; its include/
# folder is PUBLIC. Header-only modules pass no SOURCES and become INTERFACE libraries.
# Installed (cmake --install) with its headers, exported as Lantern::<name> (docs/extending.md).
function(lantern_module name)
    cmake_parse_arguments(ARG "" "NAMESPACE" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
    if(NOT ARG_NAMESPACE)
        set(ARG_NAMESPACE engine)
    endif()
    set(target lantern_${name})
    set(include_dirs $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
    if(ARG_SOURCES)
        add_library(${target} STATIC ${ARG_SOURCES})
        target_include_directories(${target} PUBLIC ${include_dirs})
        target_link_libraries(${target} PUBLIC lantern::public_options ${ARG_PUBLIC_DEPS}
                                        PRIVATE lantern::build_options ${ARG_PRIVATE_DEPS})
    else()
        add_library(${target} INTERFACE)
        target_include_directories(${target} INTERFACE ${include_dirs})
        target_link_libraries(${target} INTERFACE lantern::public_options ${ARG_PUBLIC_DEPS})
    endif()
    add_library(${ARG_NAMESPACE}::${name} ALIAS ${target})
    lantern_install_library(${target} ${name})
    install(DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endfunction()

# Installs library <target> as Lantern::<export_name> (the export set LanternTargets).
function(lantern_install_library target export_name)
    set_target_properties(${target} PROPERTIES EXPORT_NAME ${export_name})
    install(TARGETS ${target} EXPORT LanternTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
endfunction()
lantern_install_library(lantern_public_options public_options)
lantern_install_library(lantern_build_options build_options)

# lantern_executable(<name> SOURCES ... [DEPS ...] [INSTALL])
# INSTALL: `cmake --install` puts it in <prefix>/bin (the game and the user-facing tools).
function(lantern_executable name)
    cmake_parse_arguments(ARG "INSTALL" "" "SOURCES;DEPS" ${ARGN})
    add_executable(${name} ${ARG_SOURCES})
    target_link_libraries(${name} PRIVATE lantern::build_options ${ARG_DEPS})
    if(ARG_INSTALL)
        install(TARGETS ${name} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
    endif()
endfunction()

# lantern_test(<name> SOURCES ... [DEPS ...] [LABELS ...] [TIMEOUT s])
# One GoogleTest executable per module; every TEST becomes its own CTest entry.
function(lantern_test name)
    cmake_parse_arguments(ARG "" "TIMEOUT" "SOURCES;DEPS;LABELS" ${ARGN})
    if(NOT ARG_TIMEOUT)
        set(ARG_TIMEOUT 300)
    endif()
    add_executable(${name} ${ARG_SOURCES})
    target_link_libraries(${name} PRIVATE lantern::build_options lantern::test_common
                          GTest::gtest GTest::gtest_main ${ARG_DEPS})
    gtest_discover_tests(${name} DISCOVERY_MODE PRE_TEST
                         PROPERTIES LABELS "${ARG_LABELS}" TIMEOUT ${ARG_TIMEOUT})
endfunction()
