# core/image: loading/writing through OpenImageIO, sRGB, procedural textures, comparison.
sl_add_test(image SOURCES test_image.c)
