# core/image: loading/writing through OpenImageIO, sRGB, procedural textures, comparison.
sl_add_test(image SOURCES test_image.c)
# core/image/image_native.c: the native JPEG/PNG/EXR decoders against OpenImageIO, bit for bit; damaged
# files fall back to OIIO; reading them opens no OpenImageIO module.
sl_add_test(image_native SOURCES test_image_native.c)
if(SL_SANITIZE)
  # OpenImageIO's leak on damaged PNGs (tests/sanitizers/lsan.supp) is suppressed by a frame of
  # OpenImageIO's, which only the full unwinder records (libstdc++ has no frame pointers)
  set_property(TEST image_native APPEND PROPERTY ENVIRONMENT "ASAN_OPTIONS=${SL_ASAN_OPTIONS}:fast_unwind_on_malloc=0")
endif()
# core/image/image_cache.c: files only OpenImageIO reads are cached decoded, keyed by their bytes; a hit
# gives OIIO's image bit for bit without opening the module; tampered, broken and changed files; the cap.
sl_add_test(image_cache SOURCES test_image_cache.c)
