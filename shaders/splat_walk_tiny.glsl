#version 450 core
// The compute splat's walk where no particle's box holds more than 2x2
// pixel centres (compute_splat.c checks the largest sprite the view allows):
// the four candidates spelled out, without loops. On llvmpipe every loop runs
// its body at least once and every `if` runs both sides, so the rows walk
// costs a tiny sprite its loop set-up and row spans besides the ray casts:
// the 1M-particle shadow map (sprites 1.3 px) took 37% less CPU this way
// (bench/RESULTS.md). The same pixels as splat_walk_rows.glsl: the row
// spans only ever exclude pixels the ray cast rejects.

void splat_pixel(ivec2 p, vec3 centre);

void walk_pixels(ivec2 lo, ivec2 hi, vec3 centre, float reach)
{
    bvec2 second = lessThanEqual(lo + 1, hi);
    if (all(lessThanEqual(lo, hi))) {
        splat_pixel(lo, centre);
        if (second.x)
            splat_pixel(lo + ivec2(1, 0), centre);
        if (second.y)
            splat_pixel(lo + ivec2(0, 1), centre);
        if (all(second))
            splat_pixel(lo + ivec2(1, 1), centre);
    }
}
