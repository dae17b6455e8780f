# Post-processes a generated <name>.cxx: fastddsgen -typeobject makes every
# message constructor re-register all TypeObjects of its IDL file (~13 us per
# construction, and not thread-safe while discovery runs). wbi registers them
# once, where a type is needed by name (wbi::msg::register_all_types()).
# Usage: cmake -DFILE=<name>.cxx -P strip_type_registration.cmake
file(READ ${FILE} text)
string(REGEX REPLACE "// Just to register all known types\n[ \t]*register[A-Za-z0-9_]*Types\\(\\);\n" "" stripped "${text}")
if(stripped STREQUAL text AND text MATCHES "register[A-Za-z0-9_]*Types\\(\\);")
  message(FATAL_ERROR "${FILE}: the constructor registration lines were not found; fastddsgen changed?")
endif()
file(WRITE ${FILE} "${stripped}")
