# encore_add_library(NAME SOURCES... [DEPENDS targets...])
# One static library per src/ folder. Its API headers live in include/encore/<folder>/ (the only
# headers installed); its internal headers beside its sources in src/<folder>/, included as
# "<folder>/Name.h" through the PRIVATE include directory src/ (see the top CMakeLists.txt).
function(encore_add_library name)
    cmake_parse_arguments(ARG "" "" "SOURCES;DEPENDS;PRIVATE_DEPENDS" ${ARGN})
    add_library(${name} STATIC ${ARG_SOURCES})
    target_include_directories(${name}
        PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include> $<INSTALL_INTERFACE:include>
        PRIVATE ${PROJECT_SOURCE_DIR}/src)
    target_compile_features(${name} PUBLIC cxx_std_20)
    target_compile_options(${name} PRIVATE -Wall -Wextra -Wno-missing-field-initializers)
    set_target_properties(${name} PROPERTIES POSITION_INDEPENDENT_CODE ON)
    target_link_libraries(${name} PUBLIC ${ARG_DEPENDS} PRIVATE ${ARG_PRIVATE_DEPENDS})
    set_property(GLOBAL APPEND PROPERTY ENCORE_LIBRARIES ${name})
endfunction()

# The internal headers for in-tree code outside the libraries (apps, bench, python, fuzz, tests):
# link encore_internal_headers PRIVATE. Never exported: the installed package does without.
add_library(encore_internal_headers INTERFACE)
target_include_directories(encore_internal_headers INTERFACE ${PROJECT_SOURCE_DIR}/src)
