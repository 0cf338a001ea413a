# thetad_add_plugin(NAME SOURCE...): a controller plug-in, a shared module that `thetad --plugin
# NAME.so` (or THETAD_PLUGIN_PATH) loads. Its static ControllerRegistrations add controllers to the
# program that loads it. It takes thetad's headers and usage requirements (thetad::plugin_api) but
# links none of its libraries: the program provides them, so the registrations reach the
# program's one registry, not a copy of it.
function(thetad_add_plugin name)
  add_library(${name} MODULE ${ARGN})
  target_link_libraries(${name} PRIVATE thetad::plugin_api)
  set_target_properties(${name} PROPERTIES PREFIX "" CXX_STANDARD 20 CXX_STANDARD_REQUIRED ON)
endfunction()
