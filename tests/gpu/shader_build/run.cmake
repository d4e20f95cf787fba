# Drives the scratch project in this folder (cmake -P; variables from tests/gpu/CMakeLists.txt):
# 1. a good shader library builds and its lookup works;
# 2. editing a file of its include folder recompiles the shader;
# 3. a shader with a compile error fails the build, and the output carries glslang's message
#    with the file and line.
foreach(var PROJECT_DIR WORK_DIR LANTERN_CMAKE_DIR GENERATOR)
    if(NOT DEFINED ${var})
        message(FATAL_ERROR "run.cmake needs -D${var}=...")
    endif()
endforeach()

file(REMOVE_RECURSE "${WORK_DIR}")
file(COPY "${PROJECT_DIR}/" DESTINATION "${WORK_DIR}/src")
set(src "${WORK_DIR}/src")
set(build "${WORK_DIR}/build")

function(run_step what expect_success)
    execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    set(step_output "${out}${err}" PARENT_SCOPE)
    if(expect_success AND NOT rc EQUAL 0)
        message(FATAL_ERROR "${what} failed (${rc}):\n${out}${err}")
    elseif(NOT expect_success AND rc EQUAL 0)
        message(FATAL_ERROR "${what} succeeded but must fail:\n${out}${err}")
    endif()
endfunction()

run_step("configure" TRUE ${CMAKE_COMMAND} -S "${src}" -B "${build}" -G "${GENERATOR}"
         "-DLANTERN_CMAKE_DIR=${LANTERN_CMAKE_DIR}")
run_step("build check_good" TRUE ${CMAKE_COMMAND} --build "${build}" --target check_good)
run_step("run check_good" TRUE "${build}/check_good")

# The include folder is a dependency: a change there recompiles the shader.
file(WRITE "${src}/include/value.glsl" "#define VALUE 9u\n")
run_step("rebuild after an include change" TRUE ${CMAKE_COMMAND} --build "${build}" --target check_good)
if(NOT step_output MATCHES "Compiling shader good\\.comp\\.glsl")
    message(FATAL_ERROR "an include change did not recompile good.comp.glsl:\n${step_output}")
endif()

run_step("build bad_shaders" FALSE ${CMAKE_COMMAND} --build "${build}" --target bad_shaders)
if(NOT step_output MATCHES "ERROR: [^\n]*bad\\.comp\\.glsl:6: 'undeclared_name' : undeclared identifier")
    message(FATAL_ERROR "the failed build does not show glslang's message:\n${step_output}")
endif()
message(STATUS "shader build checks passed")
