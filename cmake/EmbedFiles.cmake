# encore_embed_files(OUTPUT_CPP NAMESPACE ns FUNCTION name FILES a.wgsl b.wgsl)
# Generates a .cpp defining `std::span<const EmbeddedFile> ns::name()` so that shader
# sources are compiled into the binary (no dependence on the working directory at run time).
function(encore_embed_files output)
    cmake_parse_arguments(ARG "" "NAMESPACE;FUNCTION" "FILES" ${ARGN})
    set(inputs)
    foreach(file ${ARG_FILES})
        list(APPEND inputs ${CMAKE_CURRENT_SOURCE_DIR}/${file})
    endforeach()
    add_custom_command(
        OUTPUT ${output}
        COMMAND ${CMAKE_COMMAND} -DOUTPUT=${output} -DNAMESPACE=${ARG_NAMESPACE} -DFUNCTION=${ARG_FUNCTION}
                "-DINPUTS=${inputs}" -P ${PROJECT_SOURCE_DIR}/cmake/EmbedFilesScript.cmake
        DEPENDS ${inputs} ${PROJECT_SOURCE_DIR}/cmake/EmbedFilesScript.cmake
        COMMENT "Embedding ${ARG_NAMESPACE} files"
        VERBATIM)
endfunction()
