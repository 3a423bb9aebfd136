/// A shared library that is not a CloudGraph plugin: it exports no entry point.

extern "C" __attribute__((visibility("default"))) int cloudgraph_unrelated_function() { return 42; }
