/* mesh_write_vtp.c — VTK XML PolyData (.vtp) with its arrays appended raw
 * (UInt64 block headers, little-endian): the points, the triangles as polys
 * (Int32 connectivity and offsets), and as point data the normals and the
 * mesh's attributes (speed, density, velocity, id), which ParaView colours by. */
#include <errno.h>
#include <string.h>

#include "fc_error.h"
#include "mesh_words.h"
#include "mesh_write.h"

#define VTP_BLOCKS_MAX 8          /* normals, 4 attributes, points, connectivity, offsets */
#define OFFSETS_PER_WRITE 1024u

/* One appended array: its XML description and its words (offsets are made while writing). */
typedef struct vtp_block {
    const char *section;          /* "PointData", "Points", "Polys" */
    const char *name;
    const char *type;             /* "Float32", "Int32", "UInt32" */
    unsigned components;
    const void *words;            /* NULL: the polys' offsets 3, 6, 9, ... */
    uint64_t count;               /* words */
} vtp_block;

static size_t list_blocks(const fc_surface_mesh *m, vtp_block out[VTP_BLOCKS_MAX])
{
    uint64_t v = m->vertex_count, t = m->triangle_count;
    size_t n = 0;
    out[n++] = (vtp_block){"PointData", "Normals", "Float32", 3, m->normals, 3 * v};
    if (m->speed)
        out[n++] = (vtp_block){"PointData", "speed", "Float32", 1, m->speed, v};
    if (m->density)
        out[n++] = (vtp_block){"PointData", "density", "Float32", 1, m->density, v};
    if (m->velocity)
        out[n++] = (vtp_block){"PointData", "velocity", "Float32", 3, m->velocity, 3 * v};
    if (m->id)
        out[n++] = (vtp_block){"PointData", "id", "UInt32", 1, m->id, v};
    out[n++] = (vtp_block){"Points", "Points", "Float32", 3, m->positions, 3 * v};
    out[n++] = (vtp_block){"Polys", "connectivity", "Int32", 1, m->indices, 3 * t};
    out[n++] = (vtp_block){"Polys", "offsets", "Int32", 1, NULL, t};
    return n;
}

/* The DataArray elements of one section, with their offsets into the appended data. */
static void print_section(FILE *to, const char *section, const vtp_block *blocks, size_t count)
{
    uint64_t offset = 0;
    for (size_t i = 0; i < count; i++) {
        if (strcmp(blocks[i].section, section) == 0)
            fprintf(to, "        <DataArray type=\"%s\" Name=\"%s\" NumberOfComponents=\"%u\" format=\"appended\" "
                        "offset=\"%llu\"/>\n",
                    blocks[i].type, blocks[i].name, blocks[i].components, (unsigned long long)offset);
        offset += 8 + 4 * blocks[i].count;
    }
}

static void print_xml(FILE *to, const fc_surface_mesh *m, const vtp_block *blocks, size_t count)
{
    fprintf(to, "<?xml version=\"1.0\"?>\n"
                "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
                "  <PolyData>\n"
                "    <Piece NumberOfPoints=\"%u\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" "
                "NumberOfPolys=\"%u\">\n"
                "      <PointData Normals=\"Normals\">\n",
            (unsigned)m->vertex_count, (unsigned)m->triangle_count);
    print_section(to, "PointData", blocks, count);
    fputs("      </PointData>\n      <Points>\n", to);
    print_section(to, "Points", blocks, count);
    fputs("      </Points>\n      <Polys>\n", to);
    print_section(to, "Polys", blocks, count);
    fputs("      </Polys>\n    </Piece>\n  </PolyData>\n  <AppendedData encoding=\"raw\">\n   _", to);
}

static bool write_offsets(FILE *to, uint64_t triangles)
{
    int32_t run[OFFSETS_PER_WRITE];
    for (uint64_t first = 0; first < triangles; first += OFFSETS_PER_WRITE) {
        size_t n = 0;
        for (uint64_t t = first; t < triangles && n < OFFSETS_PER_WRITE; t++)
            run[n++] = (int32_t)(3 * (t + 1));
        if (!fc_mesh_put_words(to, run, n))
            return false;
    }
    return true;
}

static bool write_block(FILE *to, const vtp_block *b)
{
    uint64_t bytes = 4 * b->count;
    uint32_t header[2] = {(uint32_t)bytes, (uint32_t)(bytes >> 32)};   /* a UInt64, little-endian */
    if (!fc_mesh_put_words(to, header, 2))
        return false;
    return b->words ? fc_mesh_put_words(to, b->words, (size_t)b->count) : write_offsets(to, b->count);
}

fc_code fc_mesh_write_vtp(FILE *to, const fc_surface_mesh *mesh, fc_error *err)
{
    vtp_block blocks[VTP_BLOCKS_MAX];
    size_t count = list_blocks(mesh, blocks);
    print_xml(to, mesh, blocks, count);
    bool ok = !ferror(to);
    for (size_t i = 0; ok && i < count; i++)
        ok = write_block(to, &blocks[i]);
    ok = ok && fputs("\n  </AppendedData>\n</VTKFile>\n", to) >= 0;
    return ok ? FC_OK : fc_error_set(err, FC_ERR_IO, "%s", strerror(errno));
}
