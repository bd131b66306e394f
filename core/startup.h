/* Start-up profile (issue 18 item 5): where the time to the first frame goes. Marks split the
 * start into phases; each phase records wall time, process CPU time (every thread: llvmpipe's
 * rasteriser threads included) and the calling thread's CPU time (on llvmpipe the shader
 * compiler, GLSL front end and LLVM code generation, runs there). --stats writes the phases
 * ("startup"), -v logs them. Also: Mesa's on-disk shader cache in the project's cache dir. */
#ifndef SL_STARTUP_H
#define SL_STARTUP_H
#include <stdbool.h>
#include <stddef.h>

typedef struct sl_startup_phase {
    char name[64];
    double wall_ms, cpu_ms, main_cpu_ms;
} sl_startup_phase;

/* Re-executes the process once (execv of the executable, same argv) with glibc's malloc asked to
 * back its memory with transparent huge pages (GLIBC_TUNABLES glibc.malloc.hugetlb=1, glibc
 * 2.35+: madvise(MADV_HUGEPAGE) on the heap and on mmap'd blocks) when first touches of 4 KiB
 * pages cost at least SL_HUGE_PAGES_MS_PER_MB (measured on a 1 MB mapping, ≈ 0.5-3 ms), unless
 * the tunable is already set, the kernel has transparent huge pages off, or SHADELAB_SMALL_PAGES
 * is set; SHADELAB_HUGE_PAGES=1 re-executes without measuring. Call it first in main(). Why: a
 * start-up writes ~300 MB of fresh memory (llvmpipe's textures and render targets, decoded
 * images); where a 4 KiB page fault costs ~11 µs (2.8 ms/MB against 0.18 ms/MB with huge pages)
 * huge pages save ~0.5 s, where it costs ~2 µs (0.4-0.5 ms/MB) clearing whole huge pages costs
 * more than it saves (docs/design-notes.md). Returns only when it did not re-execute. */
#define SL_HUGE_PAGES_MS_PER_MB 1.5
void sl_startup_huge_pages(char **argv);
/* Starts the clock (main() calls it first); marks before it count from the first mark. */
void sl_startup_begin(void);
/* Ends the current phase, naming it (printf format). Cheap; at most 64 phases are kept (the rest
 * add up in the last). */
void sl_startup_mark(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* Adds to the GLSL front-end total (glCompileShader + glLinkProgram, calling thread's CPU). */
void sl_startup_note_glsl(double main_cpu_ms, double wall_ms);
void sl_startup_glsl_total(double *main_cpu_ms, double *wall_ms, int *programs);
/* The calling thread's CPU clock in ms (for sl_startup_note_glsl). */
double sl_startup_thread_cpu_ms(void);
double sl_startup_wall_ms(void);
/* Stops recording (after the first frames); marks after it are ignored. */
void sl_startup_end(void);
bool sl_startup_recording(void);
int sl_startup_phases(const sl_startup_phase **out);

/* Points Mesa's on-disk shader cache at $SHADELAB_CACHE/mesa, else $XDG_CACHE_HOME/shadelab/mesa,
 * else $HOME/.cache/shadelab/mesa (created), unless the user set MESA_SHADER_CACHE_DIR (or the
 * older MESA_GLSL_CACHE_DIR) or disabled the cache (MESA_SHADER_CACHE_DISABLE, MESA_GLSL_CACHE_DISABLE).
 * Must run before the first GL context is created (Mesa reads it when the screen is made).
 * Writes the directory used (or "" when left to Mesa) into dir. */
void sl_startup_shader_cache(char *dir, size_t n);
#endif
