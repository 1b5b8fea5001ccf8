# cmake -DSOURCE_DIR=... -DBUILD_DIR=... -DCONSUMER_SOURCE=... -DWORK_DIR=... -DGENERATOR=...
#       -DCXX=... [-DLAUNCHER=...] -P RunConsumer.cmake
# Installs the build into a fresh prefix (cmake --install), then configures and builds
# tests/package/consumer against that prefix alone and runs it: the installed package must be
# enough for a project outside the tree to load and render a scene.
foreach(variable SOURCE_DIR BUILD_DIR CONSUMER_SOURCE WORK_DIR GENERATOR CXX)
    if(NOT DEFINED ${variable})
        message(FATAL_ERROR "RunConsumer.cmake: ${variable} is not set.")
    endif()
endforeach()

function(run what)
    execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE output
                    ERROR_VARIABLE output)
    if(NOT result EQUAL 0)
        message(FATAL_ERROR "${what} failed (${result}):\n${output}")
    endif()
    message(STATUS "${what}: done")
endfunction()

set(prefix ${WORK_DIR}/prefix)
file(REMOVE_RECURSE ${WORK_DIR})
run("Installing ${BUILD_DIR} into ${prefix}" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
# The headers installed are include/encore's, the API, and no others.
file(GLOB_RECURSE installed RELATIVE ${prefix}/include ${prefix}/include/*)
file(GLOB_RECURSE api RELATIVE ${SOURCE_DIR}/include ${SOURCE_DIR}/include/*)
if(NOT installed STREQUAL api)
    message(FATAL_ERROR "${prefix}/include holds\n  ${installed}\ninstead of include/'s\n  ${api}")
endif()

set(launcher)
if(LAUNCHER)
    set(launcher -DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER})
endif()
# Only the prefix: no package registry, so that nothing of the build tree can be found instead.
run("Configuring the consumer" ${CMAKE_COMMAND} -S ${CONSUMER_SOURCE} -B ${WORK_DIR}/build
    -G "${GENERATOR}" -DCMAKE_CXX_COMPILER=${CXX} ${launcher} -DCMAKE_BUILD_TYPE=
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF -Wno-dev)
file(STRINGS ${WORK_DIR}/build/CMakeCache.txt encore_dir REGEX "^encore_DIR:")
string(FIND "${encore_dir}" "=${prefix}/" at)
if(at EQUAL -1)
    message(FATAL_ERROR "The consumer found encore outside ${prefix} (${encore_dir}).")
endif()
run("Building the consumer" ${CMAKE_COMMAND} --build ${WORK_DIR}/build)

execute_process(COMMAND ${WORK_DIR}/build/encore_consumer ${WORK_DIR}/run
                RESULT_VARIABLE result)
if(NOT result EQUAL 0)
    message(FATAL_ERROR "The consumer failed (${result}).")
endif()
