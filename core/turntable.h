/* --turntable: the camera of each frame of one orbit around the scene (issue 19). */
#ifndef SL_TURNTABLE_H
#define SL_TURNTABLE_H
#include "camera.h"

/* The camera of frame `frame` of a `count`-frame orbit: about the vertical axis through the
 * centre of the bounds (x and z; the start camera's target when the bounds are empty), at the
 * start camera's height above its target's height and its distance, looking at the axis at the
 * target's height; yaw = start yaw + 2π·frame/count. Frame 0 is the start camera (its target
 * moved onto the axis); frame `count` would be frame 0 again: the loop is seamless. */
void sl_turntable_camera(const sl_camera_state *start, const float bounds_min[3], const float bounds_max[3], int frame,
                         int count, sl_camera_state *out);

/* The file name of frame `frame`: "DIR/STEM-007.png" from the output path (extension kept,
 * .png when it has none or is a video's), digits enough for count - 1 (at least 3). False
 * when it does not fit. */
bool sl_turntable_frame_path(const char *output, int frame, int count, char *out, size_t n);
#endif
