/// A library with a valid stamp whose entry symbols are data, not functions: calling them
/// would crash the process, so the loader must refuse it.

#include "core/Plugin.h"

extern "C" {
__attribute__((visibility("default"), used, section(".cloudgraph_plugin")))
cg::PluginStamp cloudgraph_plugin_stamp = {"CloudGraphPlugn", CLOUDGRAPH_PLUGIN_ABI_VERSION};
__attribute__((visibility("default"))) int cloudgraph_plugin_abi_version = 0;
__attribute__((visibility("default"))) int cloudgraph_plugin_register = 0;
}
