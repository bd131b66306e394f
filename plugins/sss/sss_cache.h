/* sss: an on-disk cache of the texture-space diffusion's result (the blurred, dilated irradiance),
 * keyed by everything the blur reads: the irradiance and stretch maps' texels, the profile and
 * tap parameters, the GLSL source and the GL renderer. Its purpose is start-up (issue 18 item 5):
 * a warm start renders the irradiance (needed for the key) and loads the result instead of the
 * twelve blur draws. Files: the cache folder "sss" (sdk cache.h: $SHADELAB_CACHE/sss, ...),
 * "ts-KEY.bin"; at most SSS_CACHE_FILES are kept (the oldest go). */
#ifndef SSS_CACHE_H
#define SSS_CACHE_H
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define SSS_CACHE_FILES 8

/* 64-bit hash of bytes, chained through h (start with any constant). Not cryptographic: a key of
 * content the process computed itself, not a defence against a crafted cache file (that file's
 * size and header are checked; its pixels are only ever displayed). */
uint64_t sss_hash(const void *data, size_t bytes, uint64_t h);
/* h over the files' contents (resource_dir/NAME); a missing file hashes its name. */
uint64_t sss_hash_files(const char *dir, const char *const *names, uint64_t h);
/* The cached result of `key` for a size×size map: RGBA32F texels (malloc'd, row 0 first) and which
 * sum texture held it. NULL when absent, short, or another key or size. */
float *sss_cache_load(uint64_t key, int size, int *result);
/* Writes the result (atomically: a temporary file renamed into place), then deletes the oldest
 * files beyond SSS_CACHE_FILES. false with err set when it could not. */
bool sss_cache_store(uint64_t key, int size, int result, const float *texels, char *err, size_t n);
#endif
