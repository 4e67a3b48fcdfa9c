#version 450 core
// The compute splat's walk where a typical particle's box holds about 3x3
// pixel centres (compute_splat.c chooses it by the typical sprite's size):
// those nine candidates spelled out without loops, then loops over whatever
// a larger box holds beyond them, which run no iteration unless some lane of
// the SIMD group needs one. On llvmpipe every `if` runs both sides and every
// loop its body max-over-lanes times, so small sprites pay for neither the
// rows walk's loop set-up nor its row spans: the thickness of 1M particles
// at half of 1024x768 (sprites about 2 px) took 17% less CPU than with the
// rows walk (bench/RESULTS.md). The same pixels as splat_walk_rows.glsl: its
// row spans only ever exclude pixels the ray cast rejects.

void splat_pixel(ivec2 p, vec3 centre);

void walk_pixels(ivec2 lo, ivec2 hi, vec3 centre, float reach)
{
    bvec2 second = lessThanEqual(lo + 1, hi);
    bvec2 third = lessThanEqual(lo + 2, hi);
    if (all(lessThanEqual(lo, hi))) {
        splat_pixel(lo, centre);
        if (second.x)
            splat_pixel(lo + ivec2(1, 0), centre);
        if (third.x)
            splat_pixel(lo + ivec2(2, 0), centre);
        if (second.y)
            splat_pixel(lo + ivec2(0, 1), centre);
        if (all(second))
            splat_pixel(lo + ivec2(1, 1), centre);
        if (second.y && third.x)
            splat_pixel(lo + ivec2(2, 1), centre);
        if (third.y)
            splat_pixel(lo + ivec2(0, 2), centre);
        if (third.y && second.x)
            splat_pixel(lo + ivec2(1, 2), centre);
        if (all(third))
            splat_pixel(lo + ivec2(2, 2), centre);
    }
    // Columns past the third of the first three rows (the outer loop over
    // columns, so that a box three wide ends it at once), then the rows past the third.
    for (int x = lo.x + 3; x <= hi.x; x++)
        for (int y = lo.y; y <= min(hi.y, lo.y + 2); y++)
            splat_pixel(ivec2(x, y), centre);
    for (int y = lo.y + 3; y <= hi.y; y++)
        for (int x = lo.x; x <= hi.x; x++)
            splat_pixel(ivec2(x, y), centre);
}
