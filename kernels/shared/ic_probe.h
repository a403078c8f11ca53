/* The hemisphere probe of an instant-cache record (docs/instant-caching.md §4): Ward's
 * hemisphere rays (Ward, Rubinstein & Clear 1988), kept only for the distance to the
 * nearest surface over the record. A record's validity ball is then kept inside that
 * distance, so a record never serves a point behind an occluder its probe saw (a wall
 * between two rooms, the far side of a doorway's jamb). The host traces the rays
 * (host/gi/ic_probe.h); the directions are shared code so any device could trace them.
 *
 * TS_IC_PROBE_RAYS directions: a 4 × 8 stratified grid over the unit disk (radius² × angle),
 * lifted to a cosine-weighted hemisphere about the geometric normal (Malley's method), and
 * shifted (Cranley–Patterson) by the record's key (a hash of the pixel, pass and seed it was
 * made at: IcRecord::probe_key), so records a pixel apart do not share blind spots and the
 * same record always gets the same rays. The key, not the position: the backends trace the
 * camera rays with different rounding, so three in four record positions differ in the
 * last bit between them, and a hash of those bits drew other rays for nearly every record,
 * a nearest hit up to 1.5x apart, and with it other radii and other records (a 40² Cornell
 * box, ic at 8 spp: relMSE 2.2e-5 between backends and 60% of pixels more than 1e-3 apart,
 * against 5e-12 and none with the key). */
#ifndef TS_IC_PROBE_H
#define TS_IC_PROBE_H
#include "shared/compat.h"
#include "shared/geometry.h"
#include "shared/rng.h"
#include "shared/sampling.h"

TS_NAMESPACE_BEGIN

#define TS_IC_PROBE_RAYS 32u
#define TS_IC_PROBE_RINGS 4u /* strata in radius²; TS_IC_PROBE_RAYS / TS_IC_PROBE_RINGS in angle */

/* Probe ray k (0 ≤ k < TS_IC_PROBE_RAYS) of the record surface s with key `key`, of unit
 * direction and length `reach` (scene units): hits beyond it cannot bound the record. */
TS_INLINE TsRay ts_ic_probe_ray(const TsSurface* s, uint key, uint k, float reach) {
    const uint sectors = TS_IC_PROBE_RAYS / TS_IC_PROBE_RINGS;
    TsRng rng = ts_rng_seed(key, 0x70726f62u, 0u);
    float su = ts_rng_next(&rng), sv = ts_rng_next(&rng);
    float u = ((float)(k % TS_IC_PROBE_RINGS) + su) / (float)TS_IC_PROBE_RINGS;
    float v = ((float)(k / TS_IC_PROBE_RINGS) + sv) / (float)sectors;
    TsRay r;
    r.org = ts_offset_ray_origin(s->origin, s->geo_normal, s->pos_scale);
    r.dir = ts_from_local(s->geo_normal, ts_sample_cosine_hemisphere(fmin(u, 0.99999994f), v));
    r.tmin = 0.0f;
    r.tmax = reach;
    return r;
}

TS_NAMESPACE_END

#endif /* TS_IC_PROBE_H */
