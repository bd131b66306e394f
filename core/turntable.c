/* --turntable (turntable.h). */
#include "turntable.h"
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

void sl_turntable_camera(const sl_camera_state *start, const float bmin[3], const float bmax[3], int frame, int count,
                         sl_camera_state *out) {
    *out = *start;
    float pos[3];
    sl_camera_position(start, pos);
    double axis[3] = {start->target[0], start->target[1], start->target[2]};
    if (bmin[0] <= bmax[0] && bmin[2] <= bmax[2] && isfinite(bmin[0]) && isfinite(bmax[0]) && isfinite(bmin[2]) &&
        isfinite(bmax[2])) {
        axis[0] = 0.5 * ((double)bmin[0] + bmax[0]);
        axis[2] = 0.5 * ((double)bmin[2] + bmax[2]);
    }
    double d[3] = {pos[0] - axis[0], pos[1] - axis[1], pos[2] - axis[2]};
    double dist = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (!(dist > 1e-6)) dist = start->distance > 0 ? start->distance : 1, d[0] = 0, d[1] = 0, d[2] = dist;
    double yaw0 = (d[0] == 0 && d[2] == 0) ? start->yaw : atan2(d[0], d[2]);
    double angle = count > 0 ? 2 * M_PI * (double)frame / (double)count : 0;
    for (int i = 0; i < 3; i++) out->target[i] = (float)axis[i];
    out->distance = (float)dist;
    out->pitch = (float)asin(fmax(-1.0, fmin(1.0, d[1] / dist)));
    if ((float)axis[0] == start->target[0] && (float)axis[2] == start->target[2]) {
        /* the start camera already looks at the axis: it keeps its own yaw, pitch and distance,
         * so frame 0 is exactly the start camera (not a float rounding of it) */
        yaw0 = start->yaw;
        out->pitch = start->pitch;
        out->distance = start->distance;
    }
    out->yaw = (float)remainder(yaw0 + angle, 2 * M_PI); /* within [−π, π]: no precision lost over many turns */
    out->version = start->version + 1 + (unsigned long long)frame;
}

bool sl_turntable_frame_path(const char *output, int frame, int count, char *out, size_t n) {
    const char *slash = strrchr(output, '/');
    const char *dot = strrchr(output, '.');
    if (dot && slash && dot < slash) dot = NULL;
    if (dot && dot == (slash ? slash + 1 : output)) dot = NULL; /* ".png" alone is a name, not an extension */
    const char *ext = dot ? dot : ".png";
    if (dot && (!strcasecmp(dot, ".mp4") || !strcasecmp(dot, ".mkv") || !strcasecmp(dot, ".webm") ||
                !strcasecmp(dot, ".mov") || !strcasecmp(dot, ".gif")))
        ext = ".png";
    int digits = 3;
    for (long m = 1000; m <= (long)count - 1; m *= 10) digits++;
    int stem = dot ? (int)(dot - output) : (int)strlen(output);
    int w = snprintf(out, n, "%.*s-%0*d%s", stem, output, digits, frame, ext);
    return w > 0 && (size_t)w < n;
}
