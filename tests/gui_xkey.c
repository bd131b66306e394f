/* sl-xkey: real X input for the GUI smoke test, through the XTEST extension (what a user's
 * keyboard does), so the test covers GLFW → Dear ImGui's chained callbacks → the viewer's key
 * handler. libX11 and libXtst are loaded at run time (their -dev packages are not needed).
 *   sl-xkey move:X,Y key:p key:Shift_L+1 ...      (DISPLAY must be set) */
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

typedef struct _XDisplay Display;
typedef unsigned long KeySym;

int main(int argc, char **argv) {
    void *x11 = dlopen("libX11.so.6", RTLD_NOW), *xtst = dlopen("libXtst.so.6", RTLD_NOW);
    if (!x11 || !xtst) { fprintf(stderr, "sl-xkey: libX11.so.6 / libXtst.so.6 not found\n"); return 77; }
    Display *(*open)(const char *) = (Display * (*)(const char *)) dlsym(x11, "XOpenDisplay");
    KeySym (*str_to_sym)(const char *) = (KeySym(*)(const char *))dlsym(x11, "XStringToKeysym");
    unsigned char (*sym_to_code)(Display *, KeySym) = (unsigned char (*)(Display *, KeySym))dlsym(x11, "XKeysymToKeycode");
    int (*sync)(Display *, int) = (int (*)(Display *, int))dlsym(x11, "XSync");
    int (*key)(Display *, unsigned, int, unsigned long) = (int (*)(Display *, unsigned, int, unsigned long))dlsym(xtst, "XTestFakeKeyEvent");
    int (*motion)(Display *, int, int, int, unsigned long) =
        (int (*)(Display *, int, int, int, unsigned long))dlsym(xtst, "XTestFakeMotionEvent");
    Display *d = open(NULL);
    if (!d) { fprintf(stderr, "sl-xkey: cannot open display %s\n", getenv("DISPLAY") ? getenv("DISPLAY") : "(unset)"); return 1; }
    for (int i = 1; i < argc; i++) {
        int x, y;
        if (sscanf(argv[i], "move:%d,%d", &x, &y) == 2) {
            motion(d, -1, x, y, 0);
        } else if (!strncmp(argv[i], "key:", 4)) {
            char spec[128];
            snprintf(spec, sizeof spec, "%s", argv[i] + 4);
            char *plus = strchr(spec, '+');
            unsigned mod = 0;
            if (plus) { *plus = 0; mod = sym_to_code(d, str_to_sym(spec)); }
            const char *name = plus ? plus + 1 : spec;
            unsigned code = sym_to_code(d, str_to_sym(name));
            if (!code) { fprintf(stderr, "sl-xkey: unknown key %s\n", name); return 1; }
            if (mod) key(d, mod, 1, 0);
            key(d, code, 1, 0);
            key(d, code, 0, 0);
            if (mod) key(d, mod, 0, 0);
        } else {
            fprintf(stderr, "sl-xkey: unknown argument %s\n", argv[i]);
            return 1;
        }
        sync(d, 0);
        usleep(150000); /* a few frames, so each press lands in its own frame */
    }
    return 0;
}
