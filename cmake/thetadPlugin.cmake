# thetad_add_plugin(NAME SOURCE...): a controller plug-in, a shared module that `thetad --plugin
# NAME.so` (or THETAD_PLUGIN_PATH) loads. Its static ControllerRegistrations add controllers to the
# program that loads it. It takes thetad's headers and usage requirements (thetad::plugin_api) but
# links none of its libraries: the program provides them, so the registrations reach the
# program's one registry, not a copy of it. Hidden visibility: the plug-in's own classes stay its
# own, even where the program or another plug-in has a class of the same name (the example PID's
# plug-in build is one), instead of being interposed by them.
function(thetad_add_plugin name)
  add_library(${name} MODULE ${ARGN})
  target_link_libraries(${name} PRIVATE thetad::plugin_api)
  set_target_properties(${name} PROPERTIES PREFIX "" CXX_STANDARD 20 CXX_STANDARD_REQUIRED ON
    CXX_VISIBILITY_PRESET hidden VISIBILITY_INLINES_HIDDEN ON)
endfunction()

# thetad_add_exported_plugin(NAME HEADER NAMESPACE): a plug-in that flies the controller `thetad
# export` wrote to HEADER (its namespace NAMESPACE: the label with non-identifier characters as _)
# as LABEL-exported (double) and LABEL-float (docs/onboard.md, "Fly it"). Two such plug-ins share
# the onboard templates' names but not their designs: the plug-ins' hidden visibility keeps them apart.
function(thetad_add_exported_plugin name header name_space)
  if(NOT DEFINED THETAD_EXPORTED_PLUGIN_SOURCE)  # in thetad's source tree
    set(THETAD_EXPORTED_PLUGIN_SOURCE ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/../export/plugin/exported_controller_plugin.cpp)
  endif()
  thetad_add_plugin(${name} ${THETAD_EXPORTED_PLUGIN_SOURCE} ${header})  # the header: rebuilt when it changes
  target_compile_definitions(${name} PRIVATE THETAD_EXPORTED_HEADER="${header}" THETAD_EXPORTED_NAMESPACE=${name_space})
endfunction()
