#version 450 core
// Per-particle records beside the positions (particle_attributes.c), in draw
// order; linked into the sprite programs that need more than a position.
// sphere.vert.glsl passes each sprite's draw slot, the index of its record.

struct particle_record {
    uint id;          // persistent id (or frame index): chooses the noise pattern
    float speed;      // |velocity|, 0 without velocities
};

layout(std430, binding = 0) readonly buffer particle_records {
    particle_record records[];
};

// Apart from the records: the foam state replaces them after the upload.
layout(std430, binding = 1) readonly buffer particle_amplitudes {
    float amplitudes[];   // noise amplitude multiplier from the foam state, 1 when calm
};

layout(location = 1) flat in int particle_slot;

uint particle_id()
{
    return records[particle_slot].id;
}

float particle_speed()
{
    return records[particle_slot].speed;
}

float particle_amplitude()
{
    return amplitudes[particle_slot];
}
