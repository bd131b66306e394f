/* Headless stills that stop when they are done (issue 44 item 4).
 *
 * A headless render without --frames is a still: the frames a plugin's still needs (TAA's
 * history, host set_still_frames), all at the start time. It stops earlier when
 *   - converged: from the second frame on, no display value (sRGB-encoded, [0,1]) changed by
 *     SL_STILL_CHANGE (one 8-bit step) or more since the frame before, over every pixel and
 *     channel; or
 *   - the budget ran out: `budget_s` > 0 seconds since the first frame started (its shader
 *     compilation included); at least one frame is rendered.
 * A still of one frame (nothing averages) reads nothing back. */
#ifndef SL_STILL_H
#define SL_STILL_H
#include "app.h"

#define SL_STILL_CHANGE (1.0 / 255.0)

typedef struct sl_still {
    double budget_s, t0;
    int frames;            /* frames rendered so far */
    int needed;            /* the frames the still needs (after the last frame) */
    double change;         /* the largest display change of the last frame (NaN before two) */
    const char *stopped;   /* why it stopped: "complete", "converged", "budget" */
    float *prev, *cur;
} sl_still;

/* Before the first frame. */
void sl_still_begin(sl_still *s, double budget_s);
/* After each frame: true when the still is done (see above). */
bool sl_still_done(sl_still *s, sl_app *app);
void sl_still_end(sl_still *s);
#endif
