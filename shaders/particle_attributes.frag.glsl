#version 450 core
// Per-particle records beside the positions (particle_attributes.c), in draw
// order; linked into the sprite programs that need more than a position.
// Without a geometry shader gl_PrimitiveID counts the points of the current
// draw call, so first_particle + gl_PrimitiveID is this sprite's record.

struct particle_record {
    uint id;          // persistent id (or frame index): chooses the noise pattern
    float speed;      // |velocity|, 0 without velocities
    float amplitude;  // noise amplitude multiplier from the foam state, 1 when calm
    float density;
};

layout(std430, binding = 0) readonly buffer particle_records {
    particle_record records[];
};

layout(location = 9) uniform int first_particle;   // draw slot of the call's first point

uint particle_id()
{
    return records[first_particle + gl_PrimitiveID].id;
}

float particle_speed()
{
    return records[first_particle + gl_PrimitiveID].speed;
}

float particle_amplitude()
{
    return records[first_particle + gl_PrimitiveID].amplitude;
}
