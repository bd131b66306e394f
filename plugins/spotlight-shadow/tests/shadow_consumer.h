/* What the test plugin shadow_consumer.c records, read by test_shadow_extension.c. */
#ifndef SS_SHADOW_CONSUMER_H
#define SS_SHADOW_CONSUMER_H
#include <shadelab/shadelab.h>
#include <shadelab/ext/shadow_maps.h>

#define SS_CONSUMER_GRID 32
typedef struct consumer_map {
    sl_shadow_map m;
    int points;                   /* texels with a caster, turned back into world points */
    float p[SS_CONSUMER_GRID * SS_CONSUMER_GRID][3];
    double depth_formula_error;   /* max relative |z(formula) − dot(p − position, direction)| */
    double texel_world_error;     /* relative |texel_world·size/2 − 1/proj[0]| */
    bool find_agrees;             /* find(light, face) gives the same layer as get(i) */
} consumer_map;

typedef struct consumer_results {
    bool had_extension;           /* get_extension returned the interface in the last frame */
    int runs, count;
    uint64_t version;
    consumer_map maps[32];
} consumer_results;
#endif
