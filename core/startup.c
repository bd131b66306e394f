/* Start-up profile and Mesa's shader cache location: see startup.h. */
#include "startup.h"
#include "log.h"
#include <shadelab/cache.h>
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#define MAX_PHASES 64

static sl_startup_phase phases[MAX_PHASES];
static int phase_count;
static bool started, ended;
static struct { double wall, cpu, main_cpu; } last;
static double begin_wall;

static double clock_ms(clockid_t id) {
    struct timespec ts;
    clock_gettime(id, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

static void now(double *wall, double *cpu, double *main_cpu) {
    *wall = clock_ms(CLOCK_MONOTONIC);
    *cpu = clock_ms(CLOCK_PROCESS_CPUTIME_ID);
    *main_cpu = clock_ms(CLOCK_THREAD_CPUTIME_ID);
}

/* Milliseconds per MB of first touches on 4 KiB pages: a fresh 1 MB anonymous mapping, advised
 * against huge pages, touched once per page (the cost the huge-page re-exec saves). */
static double small_page_ms_per_mb(void) {
    const size_t bytes = 1u << 20;
    char *p = mmap(NULL, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED) return 0;
#ifdef MADV_NOHUGEPAGE
    madvise(p, bytes, MADV_NOHUGEPAGE);
#endif
    double t0 = clock_ms(CLOCK_MONOTONIC);
    for (size_t i = 0; i < bytes; i += 4096) p[i] = 1;
    double ms = clock_ms(CLOCK_MONOTONIC) - t0;
    munmap(p, bytes);
    return ms;
}

void sl_startup_huge_pages(char **argv) {
    const char *set = getenv("GLIBC_TUNABLES");
    if (getenv("SHADELAB_SMALL_PAGES") || (set && strstr(set, "glibc.malloc.hugetlb"))) return;
    /* "always [madvise] never": madvise is what the tunable uses; "[never]" would make it a no-op */
    char mode[128] = "";
    FILE *f = fopen("/sys/kernel/mm/transparent_hugepage/enabled", "r");
    if (!f) return;
    size_t n = fread(mode, 1, sizeof mode - 1, f);
    fclose(f);
    mode[n] = 0;
    if (!strstr(mode, "[always]") && !strstr(mode, "[madvise]")) return;
    /* Only where small pages are slow: 2.8 ms/MB on the VM the re-exec was measured on (a warm
     * head start 3.05 → 2.54 s with it), 0.4-0.5 ms/MB on one where it made a cold head start
     * 0-9 % slower (clearing whole huge pages, 0.85 s of system time against 0.32 s; interleaved
     * A/B; docs/design-notes.md, "Start-up"). SHADELAB_HUGE_PAGES=1 re-executes regardless. */
    const char *force = getenv("SHADELAB_HUGE_PAGES");
    if (!(force && *force && strcmp(force, "0")) && small_page_ms_per_mb() < SL_HUGE_PAGES_MS_PER_MB) return;
    char value[4096];
    int len = snprintf(value, sizeof value, "%s%sglibc.malloc.hugetlb=1", set ? set : "", set && *set ? ":" : "");
    if (len < 0 || (size_t)len >= sizeof value || setenv("GLIBC_TUNABLES", value, 1) != 0) return;
    /* by the executable's own path: the kernel names the process after the file exec'd (what ps,
     * top and pkill show), and /proc/self/exe would name it "exe"; that link only when the path
     * cannot be read or no longer execs (the file was replaced: " (deleted)") */
    char self[4096];
    ssize_t k = readlink("/proc/self/exe", self, sizeof self - 1);
    if (k > 0) {
        self[k] = 0;
        execv(self, argv);
    }
    execv("/proc/self/exe", argv);
    /* no /proc (a chroot, a sandbox): go on with small pages, and do not pass the setting on */
    if (set) setenv("GLIBC_TUNABLES", set, 1);
    else unsetenv("GLIBC_TUNABLES");
}

void sl_startup_begin(void) {
    phase_count = 0;
    started = true;
    ended = false;
    now(&last.wall, &last.cpu, &last.main_cpu);
    begin_wall = last.wall;
}

void sl_startup_mark(const char *fmt, ...) {
    if (!started || ended) return;
    double w, c, m;
    now(&w, &c, &m);
    sl_startup_phase *p;
    if (phase_count < MAX_PHASES) {
        p = &phases[phase_count++];
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(p->name, sizeof p->name, fmt, ap);
        va_end(ap);
    } else {
        p = &phases[MAX_PHASES - 1];
        snprintf(p->name, sizeof p->name, "(more phases)");
    }
    /* progress (stderr): a phase that took over a second is named as it ends */
    if (w - last.wall > 1000)
        SL_INFO("start-up: %s took %.1f s (%.1f s since start)", p->name, (w - last.wall) / 1e3, (w - begin_wall) / 1e3);
    p->wall_ms += w - last.wall;
    p->cpu_ms += c - last.cpu;
    p->main_cpu_ms += m - last.main_cpu;
    last.wall = w, last.cpu = c, last.main_cpu = m;
}

static double glsl_cpu, glsl_wall;
static int glsl_programs;

void sl_startup_note_glsl(double main_cpu_ms, double wall_ms) {
    glsl_cpu += main_cpu_ms;
    glsl_wall += wall_ms;
    glsl_programs++;
}

void sl_startup_glsl_total(double *main_cpu_ms, double *wall_ms, int *programs) {
    *main_cpu_ms = glsl_cpu;
    *wall_ms = glsl_wall;
    *programs = glsl_programs;
}

double sl_startup_thread_cpu_ms(void) { return clock_ms(CLOCK_THREAD_CPUTIME_ID); }
double sl_startup_wall_ms(void) { return clock_ms(CLOCK_MONOTONIC); }

void sl_startup_end(void) { ended = true; }
bool sl_startup_recording(void) { return started && !ended; }

int sl_startup_phases(const sl_startup_phase **out) {
    *out = phases;
    return phase_count;
}

static bool set_env(const char *name) { const char *v = getenv(name); return v && *v; }

void sl_startup_shader_cache(char *dir, size_t n) {
    dir[0] = 0;
    /* the user's choice wins: a directory of theirs, or the cache switched off */
    if (set_env("MESA_SHADER_CACHE_DIR") || set_env("MESA_GLSL_CACHE_DIR") || set_env("MESA_SHADER_CACHE_DISABLE") ||
        set_env("MESA_GLSL_CACHE_DISABLE"))
        return;
    char d[4096];
    if (!sl_cache_dir("mesa", d, sizeof d, true)) return; /* Mesa falls back to its own default */
    /* Mesa 22 reads MESA_SHADER_CACHE_DIR; releases before 21 read MESA_GLSL_CACHE_DIR */
    setenv("MESA_SHADER_CACHE_DIR", d, 1);
    setenv("MESA_GLSL_CACHE_DIR", d, 1);
    snprintf(dir, n, "%s", d);
}
