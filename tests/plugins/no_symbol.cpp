// A shared object that is not a graspkit plugin: it exports no graspkit_plugin_v1.
extern "C" __attribute__((visibility("default"))) int some_other_library_function() {
  return 7;
}
