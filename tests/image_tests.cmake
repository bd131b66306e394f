# core/image: loading/writing through OpenImageIO, sRGB, procedural textures, comparison.
sl_add_test(image SOURCES test_image.c)
# core/image/image_native.c: the native JPEG/PNG/EXR decoders against OpenImageIO, bit for bit; damaged
# files fall back to OIIO; reading them opens no OpenImageIO module.
sl_add_test(image_native SOURCES test_image_native.c)
