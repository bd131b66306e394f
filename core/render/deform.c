/* Deformed meshes on the GPU (sl_mesh_deform: glTF morph targets and skins). Each frame, before
 * any pass, the CPU evaluates every deformed mesh's joint matrices (from the posed nodes) and
 * morph weights (animated by sl_scene_animate); when they changed, a compute shader
 * (shaders/deform.comp) writes the mesh's positions, normals and tangents into the vertex buffers
 * every draw reads, so the forward pass, depth pre-pass, shadow maps and plugins' programs all draw
 * the same deformed shape and no program needs a variant; a static mesh runs nothing. With motion
 * vectors, the positions alternate between two buffers: a new pose is written beside the last
 * one, which vertex attribute 5 (the previous frame's positions; a static mesh's own) then reads. */
#include "render/renderer_internal.h"
#include "log.h"
#include <shadelab/gl.h>
#include <cglm/cglm.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

struct gpu_deform {
    unsigned rest, targets, influences, frame; /* buffers (targets/influences: 0 when none) */
    unsigned pos[2];      /* positions: the mesh's vbo[0] and a second one, written in turn */
    int current;          /* pos[current] holds the last pose */
    int vertex_count, joint_count;
    float *frame_data;    /* 16 × joint_count + target_count floats */
    uint64_t key;         /* hash of the last frame_data dispatched */
    bool posed;           /* dispatched at least once */
    bool prev_behind;     /* attribute 5 reads the pose before the last one */
};

static unsigned buffer_of(const void *data, size_t bytes) {
    unsigned b = 0;
    glCreateBuffers(1, &b);
    glNamedBufferStorage(b, bytes ? bytes : 4, data, bytes && data ? 0 : GL_DYNAMIC_STORAGE_BIT);
    return b;
}

/* The rest shape, 10 floats per vertex (shaders/deform.comp). */
static float *rest_of(const sl_mesh_data *m) {
    float *r = calloc((size_t)m->vertex_count * 10 + 1, sizeof(float));
    for (int v = 0; r && v < m->vertex_count; v++) {
        memcpy(r + 10 * v, m->positions + 3 * v, 3 * sizeof(float));
        if (m->normals) memcpy(r + 10 * v + 3, m->normals + 3 * v, 3 * sizeof(float));
        if (m->tangents) memcpy(r + 10 * v + 6, m->tangents + 4 * v, 4 * sizeof(float));
        else r[10 * v + 9] = 1;
    }
    return r;
}

/* The targets' displacements interleaved per target and vertex (position, normal, tangent). */
static float *targets_of(const sl_mesh_data *m, const sl_mesh_deform *d) {
    size_t n = (size_t)m->vertex_count, T = (size_t)d->target_count;
    float *t = calloc(n * T * 9 + 1, sizeof(float));
    const float *src[3] = {d->target_positions, d->target_normals, d->target_tangents};
    for (size_t k = 0; t && k < T; k++)
        for (size_t v = 0; v < n; v++)
            for (int a = 0; a < 3; a++)
                if (src[a]) memcpy(t + (k * n + v) * 9 + 3 * a, src[a] + (k * n + v) * 3, 3 * sizeof(float));
    return t;
}

/* Joint indices then weights (as float bits), influences per vertex. */
static uint32_t *influences_of(const sl_mesh_data *m, const sl_mesh_deform *d) {
    size_t n = (size_t)m->vertex_count * (size_t)d->influences;
    uint32_t *u = malloc(sizeof(uint32_t) * (2 * n + 1));
    for (size_t i = 0; u && i < n; i++) {
        u[i] = d->joints[i];
        memcpy(&u[n + i], &d->joint_weights[i], 4);
    }
    return u;
}

void sl_deform_upload(sl_app *app, int mi) {
    const sl_mesh *mesh = &app->scene.meshes[mi];
    const sl_mesh_deform *d = mesh->deform;
    gpu_mesh *g = &R(app)->meshes[mi];
    if (!d || !mesh->data.vertex_count) return;
    struct gpu_deform *gd = calloc(1, sizeof *gd);
    if (!gd) {
        SL_ERROR("mesh \"%s\": out of memory for its deformation: drawn at rest", mesh->name);
        return;
    }
    const sl_skin *skin = d->skin >= 0 ? &app->scene.skins[d->skin] : NULL;
    gd->vertex_count = mesh->data.vertex_count;
    gd->joint_count = skin ? skin->joint_count : 0;
    float *rest = rest_of(&mesh->data), *targets = d->target_count ? targets_of(&mesh->data, d) : NULL;
    uint32_t *infl = skin && d->influences ? influences_of(&mesh->data, d) : NULL;
    size_t frame_floats = 16 * (size_t)gd->joint_count + (size_t)d->target_count;
    gd->frame_data = calloc(frame_floats + 1, sizeof(float));
    if (!rest || (d->target_count && !targets) || (skin && d->influences && !infl) || !gd->frame_data) {
        SL_ERROR("mesh \"%s\": out of memory for its deformation: drawn at rest", mesh->name);
        free(rest), free(targets), free(infl), free(gd->frame_data), free(gd);
        return;
    }
    size_t n = (size_t)gd->vertex_count;
    gd->rest = buffer_of(rest, n * 10 * sizeof(float));
    if (targets) gd->targets = buffer_of(targets, n * (size_t)d->target_count * 9 * sizeof(float));
    if (infl) gd->influences = buffer_of(infl, n * (size_t)d->influences * 2 * sizeof(uint32_t));
    gd->frame = buffer_of(NULL, (frame_floats + 1) * sizeof(float));
    gd->pos[0] = g->vbo[0];
    gd->pos[1] = buffer_of(NULL, n * 3 * sizeof(float));
    free(rest), free(targets), free(infl);
    g->deform = gd;
}

void sl_deform_free(gpu_mesh *g) {
    struct gpu_deform *gd = g->deform;
    if (!gd) return;
    unsigned b[5] = {gd->rest, gd->targets, gd->influences, gd->frame, gd->pos[1]};
    for (int i = 0; i < 5; i++)
        if (b[i]) glDeleteBuffers(1, &b[i]);
    free(gd->frame_data), free(gd);
    g->deform = NULL;
}

/* The compute program, built at the first deformed mesh's first frame; 0 after a failure (logged
 * once: the meshes stay at rest). */
static unsigned deform_program(sl_renderer *r) {
    if (r->deform_prog || r->deform_failed) return r->deform_prog;
    sl_source src;
    sl_source_init(&src);
    char err[2048] = "", log[4096] = "";
    sl_sb_append(&src.text, "#version 450 core\n");
    bool ok = sl_source_include(&src, "sl:deform.comp", err, sizeof err);
    unsigned sh = ok ? glCreateShader(GL_COMPUTE_SHADER) : 0, prog = 0;
    if (ok) {
        const char *text = src.text.s;
        glShaderSource(sh, 1, &text, NULL);
        glCompileShader(sh);
        int status = 0;
        glGetShaderiv(sh, GL_COMPILE_STATUS, &status);
        if (status) {
            prog = glCreateProgram();
            glAttachShader(prog, sh);
            glLinkProgram(prog);
            glGetProgramiv(prog, GL_LINK_STATUS, &status);
            if (!status) glGetProgramInfoLog(prog, sizeof log, NULL, log);
        } else {
            glGetShaderInfoLog(sh, sizeof log, NULL, log);
        }
        ok = status != 0;
        sl_source_map_log(&src, log, err, sizeof err);
        glDeleteShader(sh);
    }
    sl_source_free(&src);
    if (!ok) {
        if (prog) glDeleteProgram(prog);
        SL_ERROR("the deformation program (shaders/deform.comp) failed: %s; skinned and morphing meshes are drawn at rest", err);
        r->deform_failed = true;
        return 0;
    }
    r->deform_prog = prog;
    return prog;
}

/* This frame's joint matrices, N⁻¹ · world(joint) · inverse bind (N: the drawing node's world
 * matrix; identity when it has no inverse), then the weights relative to the rest shape's. */
static void frame_data(sl_app *app, const sl_mesh_deform *d, struct gpu_deform *gd) {
    const sl_scene *s = &app->scene;
    float *out = gd->frame_data;
    if (gd->joint_count) {
        mat4 inv;
        glm_mat4_inv((vec4 *)s->nodes[d->node].world, inv);
        bool usable = true;
        for (int i = 0; i < 16; i++) usable = usable && isfinite(((float *)inv)[i]);
        if (!usable || fabsf(glm_mat4_det((vec4 *)s->nodes[d->node].world)) < 1e-30f) glm_mat4_identity(inv);
        const sl_skin *skin = &s->skins[d->skin];
        for (int j = 0; j < gd->joint_count; j++) {
            mat4 jw;
            glm_mat4_mul(inv, (vec4 *)s->nodes[skin->joints[j]].world, jw);
            glm_mat4_mul(jw, (vec4 *)(skin->inverse_bind + 16 * j), (vec4 *)(out + 16 * j));
        }
    }
    for (int t = 0; t < d->target_count; t++) out[16 * gd->joint_count + t] = d->weights[t] - d->rest_weights[t];
}

/* Attribute 0 reads pos[current]; attribute 5 (the previous frame's positions) pos[prev]. */
static void bind_positions(gpu_mesh *g, int prev) {
    struct gpu_deform *gd = g->deform;
    glVertexArrayVertexBuffer(g->vao, 0, gd->pos[gd->current], 0, 3 * sizeof(float));
    glVertexArrayVertexBuffer(g->vao, 5, gd->pos[prev], 0, 3 * sizeof(float));
}

void sl_deform_frame(sl_app *app) {
    sl_renderer *r = R(app);
    sl_scene *s = &app->scene;
    bool dispatched = false;
    for (int mi = 0; mi < s->mesh_count; mi++) {
        gpu_mesh *g = &r->meshes[mi];
        struct gpu_deform *gd = g->deform;
        if (!gd) continue;
        const sl_mesh_deform *d = s->meshes[mi].deform;
        size_t floats = 16 * (size_t)gd->joint_count + (size_t)d->target_count;
        frame_data(app, d, gd);
        uint64_t key = sl_hash64(gd->frame_data, floats * sizeof(float), 0x5eed);
        if (gd->posed && key == gd->key) { /* unchanged: last frame's pose is this frame's */
            if (gd->prev_behind) bind_positions(g, gd->current);
            gd->prev_behind = false;
            continue;
        }
        unsigned prog = deform_program(r);
        if (!prog) return;
        int last = gd->current;
        gd->current = 1 - last; /* the new pose goes beside the last one (the first: no last one) */
        glNamedBufferSubData(gd->frame, 0, (long)(floats * sizeof(float)), gd->frame_data);
        glUseProgram(prog);
        glUniform1i(glGetUniformLocation(prog, "sl_vertex_count"), gd->vertex_count);
        glUniform1i(glGetUniformLocation(prog, "sl_target_count"), d->target_count);
        glUniform1i(glGetUniformLocation(prog, "sl_influences"), gd->influences ? d->influences : 0);
        glUniform1i(glGetUniformLocation(prog, "sl_joint_count"), gd->joint_count);
        unsigned bind[7] = {gd->rest, gd->targets ? gd->targets : gd->rest, gd->influences ? gd->influences : gd->rest,
                            gd->frame, gd->pos[gd->current], g->vbo[1], g->vbo[2]};
        for (int b = 0; b < 7; b++) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, (unsigned)b, bind[b]);
        glDispatchCompute((unsigned)(gd->vertex_count + 63) / 64, 1, 1);
        bind_positions(g, gd->posed ? last : gd->current);
        gd->prev_behind = gd->posed;
        gd->posed = true, gd->key = key;
        dispatched = true;
    }
    if (dispatched) {
        glMemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
        for (int b = 0; b < 7; b++) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, (unsigned)b, 0);
        glUseProgram(0);
    }
}
