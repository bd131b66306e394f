/* envmap's screen-space reflections (reflections=screen): reflections.c. */
#ifndef ENVMAP_REFLECTIONS_H
#define ENVMAP_REFLECTIONS_H
#include <shadelab/shadelab.h>
#include <shadelab/gl.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

typedef struct em_reflections {
    const sl_host *host;
    bool (*lit)(void *);    /* envmap has an environment to light with */
    void *lit_user;
    sl_target_desc scene_targets[3], trace_target, resolve_target;
    struct sl_program *trace_prog, *resolve_prog;
    int unit_found;         /* the forward programs' */
    unsigned color, depth;  /* the scene's image with mips (envmap's own), its depth (the pass's) */
    unsigned found;         /* what the rays found, filtered (the resolve pass's) */
    unsigned nothing;       /* 1x1, weight 0: bound until the trace pass has run */
    int w, h, levels;
    uint32_t generation;    /* moves when the image is freed: the pass draws it again */
    float view_proj[16], depth_lin[4], texel[2], length;
} em_reflections;

sl_status em_reflections_create(em_reflections *r, const sl_host *host, bool (*lit)(void *), void *lit_user);
sl_status em_reflections_activate(em_reflections *r); /* GL current */
bool em_reflections_on(const em_reflections *r);
/* In envmap's bind callback: the uniforms of a program that traces reflected rays. */
void em_reflections_bind(em_reflections *r, unsigned prog);
void em_reflections_free(em_reflections *r);
#endif
