# Drives tests/extend (cmake -P; variables from its CMakeLists.txt):
# 1. `cmake --install` of the build tree into a scratch prefix (libraries, headers, shaders,
#    the package files, and the game and tools in bin/, each run with --version);
# 2. each example (examples/<name>/, a CMake project of its own) configures against that
#    prefix alone (find_package(Lantern)), builds, and passes its own ctest tests;
# 3. no compile command of an example carries Lantern's build flags (warnings, -Werror,
#    sanitizers): they are PRIVATE to Lantern's libraries.
foreach(var LANTERN_BINARY_DIR EXAMPLES_DIR WORK_DIR GENERATOR)
    if(NOT DEFINED ${var})
        message(FATAL_ERROR "run.cmake needs -D${var}=...")
    endif()
endforeach()

file(REMOVE_RECURSE "${WORK_DIR}")
set(prefix "${WORK_DIR}/prefix")

function(run_step what)
    execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
        message(FATAL_ERROR "${what} failed (${rc}):\n${out}${err}")
    endif()
endfunction()

run_step("install" ${CMAKE_COMMAND} --install "${LANTERN_BINARY_DIR}" --prefix "${prefix}")
foreach(required lib/cmake/Lantern/LanternConfig.cmake lib/cmake/Lantern/LanternConfigVersion.cmake
                 lib/cmake/Lantern/LanternShaders.cmake include/lantern/systems/gi_frame.hpp
                 share/lantern/shaders/include/lantern/gi_common.glsl)
    if(NOT EXISTS "${prefix}/${required}")
        message(FATAL_ERROR "the installed package lacks ${required}")
    endif()
endforeach()

# The game and the user-facing tools are installed and run from the prefix.
foreach(exe lantern lantern-render lantern-bake lantern-bench)
    if(NOT EXISTS "${prefix}/bin/${exe}")
        message(FATAL_ERROR "the installed package lacks bin/${exe}")
    endif()
    run_step("${exe} --version" "${prefix}/bin/${exe}" --version)
endforeach()

file(GLOB examples LIST_DIRECTORIES true "${EXAMPLES_DIR}/*")
set(count 0)
foreach(example IN LISTS examples)
    if(NOT EXISTS "${example}/CMakeLists.txt")
        continue()
    endif()
    get_filename_component(name "${example}" NAME)
    set(build "${WORK_DIR}/${name}")
    run_step("configure ${name}" ${CMAKE_COMMAND} -S "${example}" -B "${build}" -G "${GENERATOR}"
             "-DCMAKE_PREFIX_PATH=${prefix}" -DCMAKE_BUILD_TYPE=Release -DCMAKE_EXPORT_COMPILE_COMMANDS=ON)
    run_step("build ${name}" ${CMAKE_COMMAND} --build "${build}")
    run_step("test ${name}" ${CMAKE_CTEST_COMMAND} --test-dir "${build}" --output-on-failure)
    file(READ "${build}/compile_commands.json" commands)
    foreach(flag -Wshadow -Werror -fsanitize)
        string(FIND "${commands}" "${flag}" at)
        if(NOT at EQUAL -1)
            message(FATAL_ERROR "${name} is compiled with Lantern's build flag ${flag}:\n${commands}")
        endif()
    endforeach()
    math(EXPR count "${count} + 1")
    message(STATUS "${name}: configured, built and tested against ${prefix}")
endforeach()
if(count EQUAL 0)
    message(FATAL_ERROR "no example found in ${EXAMPLES_DIR}")
endif()
