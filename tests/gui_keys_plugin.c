/* Test plugin for key-binding conflicts, built twice (KEYS_ID "keys-a" and "keys-b"): both
 * want the same keys, and some of those keys belong to the viewer. */
#include <shadelab/shadelab.h>

static sl_status keys_create(const sl_host *host, void **user) {
    const sl_param_desc flag = {.struct_size = sizeof flag, .id = "flag", .type = SL_PARAM_BOOL,
                                .description = "Toggled by this plugin's key 1."};
    const sl_param_desc mode = {.struct_size = sizeof mode, .id = "mode", .type = SL_PARAM_ENUM,
                                .enum_values = (const char *const[]){"one", "two", "three", 0},
                                .description = "Cycled by this plugin's key 2."};
    if (host->add_param(host, &flag) != SL_OK || host->add_param(host, &mode) != SL_OK) return SL_ERR_FAILED;
    const sl_key_desc keys[] = {
        {.struct_size = sizeof(sl_key_desc), .key = "1", .description = KEYS_ID " flag", .param = "flag"},
        {.struct_size = sizeof(sl_key_desc), .key = "2", .description = KEYS_ID " mode", .param = "mode"},
        {.struct_size = sizeof(sl_key_desc), .key = "p", .description = KEYS_ID " wants the screenshot key", .param = "flag"},
        {.struct_size = sizeof(sl_key_desc), .key = "W", .description = KEYS_ID " wants a fly key", .param = "flag"},
        {.struct_size = sizeof(sl_key_desc), .key = "Ctrl+K", .description = KEYS_ID " invalid key", .param = "flag"},
    };
    for (unsigned i = 0; i < sizeof keys / sizeof *keys; i++)
        if (host->add_key(host, &keys[i]) != SL_OK) return SL_ERR_FAILED;
    *user = (void *)host;
    return SL_OK;
}

static const sl_plugin_desc desc = {SL_PLUGIN_HEADER, .id = KEYS_ID, .version = "1",
                                    .description = "key conflict test plugin", .create = keys_create};
SL_DEFINE_PLUGIN(desc)
