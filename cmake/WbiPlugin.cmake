# wbi_add_plugin(<name> SOURCES ... [DEPS ...]): a plugin (wbi/plugin.hpp), a
# shared library loaded by name at run time: lib<name>.so, which a deploy
# file names as `plugins: [<name>]` (found through WBI_PLUGIN_PATH, the deploy
# file's folder or wbi's own plugin folder) or by its path. Installed with
# the wbi package (find_package(wbi) gives this function) so that a lab's
# project builds its plugins the same way as wbi builds its own.
#
# Its symbols are hidden but for the entry point, so that two plugins never
# bind to each other's code; it links the wbi libraries it uses (shared, one
# copy in the process).
function(wbi_add_plugin name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(${name} MODULE ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE wbi::vocabulary ${ARG_DEPS})
  set_target_properties(${name} PROPERTIES
    PREFIX "lib"
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON)
endfunction()
