#ifndef SL_CORE_PLUGIN_H
#define SL_CORE_PLUGIN_H
#include <shadelab/shadelab.h>
extern const sl_plugin_desc sl_core_plugin;
#endif
