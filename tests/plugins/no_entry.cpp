// A shared library that is not a motus plug-in: it has no entry point motus_plugin.
extern "C" __attribute__((visibility("default"))) int some_function() { return 42; }
