# embed_files(<out-var> DIR <dir> NAMESPACE <ns> FUNCTION <fn>): generates a source file that
# embeds every file of <dir> (see embed_files.cmake) and stores its path in <out-var>.
function(embed_files out_var)
  cmake_parse_arguments(E "" "DIR;NAMESPACE;FUNCTION" "" ${ARGN})
  file(GLOB inputs CONFIGURE_DEPENDS ${E_DIR}/*)
  set(out ${CMAKE_CURRENT_BINARY_DIR}/${E_FUNCTION}.cpp)
  add_custom_command(
    OUTPUT ${out}
    COMMAND ${CMAKE_COMMAND} -DDIR=${E_DIR} -DOUT=${out} -DNS=${E_NAMESPACE} -DFUNC=${E_FUNCTION}
            -P ${PROJECT_SOURCE_DIR}/cmake/embed_files.cmake
    DEPENDS ${inputs} ${PROJECT_SOURCE_DIR}/cmake/embed_files.cmake
    COMMENT "Embedding ${E_DIR}")
  set(${out_var} ${out} PARENT_SCOPE)
endfunction()
