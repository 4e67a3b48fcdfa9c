/* image_encoder.cpp — fc_encode_image over OpenImageIO (JPEG, EXR) and
 * fluidcast's own PNG writer (png_encoder.h), the server's only C++.
 *
 * OpenImageIO's writers are handed an in-memory IOVecOutput proxy so nothing touches the
 * file system. Every exception stops at the C boundary (fc_encode_image). */
#include "image_encoder.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstring>
#include <exception>
#include <new>
#include <string>
#include <type_traits>
#include <vector>

#include "fc_error.h"
#include "png_encoder.h"

namespace {

using OIIO::ImageOutput;
using OIIO::ImageSpec;
using OIIO::TypeDesc;

size_t bytes_per_channel(fc_pixel_type type)
{
    return type == FC_PIXEL_F32 ? sizeof(float) : 1;
}

/* Own size computation: fc_image_size lives in fc_render, which the encoder
 * must not pull in (it would drag GL into every encoder user). */
size_t pixel_bytes(const fc_image &img)
{
    return (size_t)img.width * img.height * img.channels * bytes_per_channel(img.type);
}

fc_code check_image(const fc_image *img, fc_error *err)
{
    if (!img || !img->pixels || img->width == 0 || img->height == 0)
        return fc_error_set(err, FC_ERR_USAGE, "encode: empty image");
    if (img->channels != 1 && img->channels != 3 && img->channels != 4)
        return fc_error_set(err, FC_ERR_USAGE, "encode: %u channels (expected 1, 3 or 4)", img->channels);
    /* C callers may store any value in the enum; in C++ loading one outside the
     * enumerators' range is undefined, so the check reads the raw integer. */
    std::underlying_type_t<fc_pixel_type> type;
    std::memcpy(&type, &img->type, sizeof type);
    if (type != FC_PIXEL_U8 && type != FC_PIXEL_F32)
        return fc_error_set(err, FC_ERR_USAGE, "encode: unknown pixel type %lld", (long long)type);
    return FC_OK;
}

/* The sRGB transfer applies to the R,G,B of an RGBA image only: alpha and the
 * channels of an AOV (1: depth-like, 3: normal) are data, scaled linearly. */
bool carries_srgb(uint32_t channel, uint32_t channels)
{
    return channels == 4 && channel < 3;
}

float srgb_encode(float linear)
{
    return linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

float srgb_decode(float encoded)
{
    return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

uint8_t float_to_u8(float value, bool srgb)
{
    /* NaN fails both comparisons and lands on 0 rather than undefined behaviour. */
    float clamped = value > 0.0f ? (value < 1.0f ? value : 1.0f) : 0.0f;
    if (srgb)
        clamped = srgb_encode(clamped);
    return (uint8_t)std::lround(clamped * 255.0f);
}

/* Display-ready 8-bit samples, keeping the first `out_channels` channels
 * (JPEG has no alpha). */
std::vector<uint8_t> to_display_u8(const fc_image &img, uint32_t out_channels)
{
    size_t pixels = (size_t)img.width * img.height;
    std::vector<uint8_t> out(pixels * out_channels);
    for (size_t i = 0; i < pixels; i++) {
        for (uint32_t c = 0; c < out_channels; c++) {
            size_t src = i * img.channels + c;
            out[i * out_channels + c] =
                img.type == FC_PIXEL_U8 ? static_cast<const uint8_t *>(img.pixels)[src]
                                        : float_to_u8(static_cast<const float *>(img.pixels)[src],
                                                      carries_srgb(c, img.channels));
        }
    }
    return out;
}

/* Linear float samples for EXR: 8-bit colour is sRGB-encoded, so it is decoded. */
std::vector<float> to_linear_f32(const fc_image &img)
{
    size_t samples = (size_t)img.width * img.height * img.channels;
    std::vector<float> out(samples);
    if (img.type == FC_PIXEL_F32) {
        std::memcpy(out.data(), img.pixels, samples * sizeof(float));
        return out;
    }
    const uint8_t *src = static_cast<const uint8_t *>(img.pixels);
    for (size_t i = 0; i < samples; i++) {
        float unit = src[i] / 255.0f;
        out[i] = carries_srgb((uint32_t)(i % img.channels), img.channels) ? srgb_decode(unit) : unit;
    }
    return out;
}

fc_code append_bytes(fc_buf *out, const void *data, size_t size, fc_error *err)
{
    if (!fc_buf_reserve(out, size))
        return fc_error_set(err, FC_ERR_NOMEM, "encode: cannot grow the output buffer by %zu bytes", size);
    std::memcpy(out->data + out->len, data, size);
    out->len += size;
    return FC_OK;
}

/* Runs one OpenImageIO writer into memory and appends the file's bytes to out. */
fc_code write_in_memory(const char *writer, const ImageSpec &spec, TypeDesc type, const void *pixels,
                        fc_buf *out, fc_error *err)
{
    std::vector<unsigned char> file;
    OIIO::Filesystem::IOVecOutput proxy(file);
    auto output = ImageOutput::create(writer, &proxy);
    if (!output)
        return fc_error_set(err, FC_ERR_ENCODE, "encode: no OpenImageIO %s writer: %s", writer,
                            OIIO::geterror().c_str());
    /* Nothing is opened under this name (the proxy receives the bytes); it only appears in messages. */
    std::string name = std::string("memory.") + writer;
    if (!output->open(name, spec) || !output->write_image(type, pixels) || !output->close())
        return fc_error_set(err, FC_ERR_ENCODE, "encode: %s: %s", writer, output->geterror().c_str());
    return append_bytes(out, file.data(), file.size(), err);
}

/* Whether every pixel of 8-bit RGBA rows has alpha 255. */
bool opaque(const uint8_t *rgba, size_t pixels)
{
    uint8_t all = 255;
    for (size_t i = 0; i < pixels; i++)
        all &= rgba[4 * i + 3];
    return all == 255;
}

/* PNG through fluidcast's own writer (png_encoder.h): the same zlib levels
 * and SUB filter OpenImageIO's writer was given before, deflated in strips on
 * several threads; OpenImageIO's writer deflates on one. An RGBA image whose
 * every pixel is opaque (a colour image always is) is written as RGB: a
 * quarter fewer bytes to filter and deflate, the file 8% smaller, the same
 * pixels decoded (bench/RESULTS.md). */
fc_code encode_png(const fc_image &img, uint32_t level, fc_buf *out, fc_error *err)
{
    if (level > FC_PNG_MAX_COMPRESSION)
        return fc_error_set(err, FC_ERR_USAGE, "encode: PNG compression %u outside 0..%u", level,
                            FC_PNG_MAX_COMPRESSION);
    fc_png_rows rows = {nullptr, img.width, img.height, img.channels, 0};
    std::vector<uint8_t> display;
    if (img.type == FC_PIXEL_U8) {
        rows.pixels = static_cast<const uint8_t *>(img.pixels);
    } else {
        display = to_display_u8(img, img.channels);
        rows.pixels = display.data();
    }
    if (img.channels == 4 && opaque(rows.pixels, (size_t)img.width * img.height)) {
        rows.channels = 3;
        rows.stride = 4;
    }
    return fc_png_encode(&rows, level, 0, out, err);
}

/* libjpeg's own default, which OpenImageIO keeps unless told, is 4:2:0; a
 * snapshot asks for 4:4:4 explicitly. Both stay baseline with the standard
 * Huffman tables and the accurate integer DCT: measured, optimised tables or
 * progressive files cost more time than they save bytes at these sizes, and
 * the fast DCT loses precision (bench/RESULTS.md). */
const char *jpeg_sampling_name(const fc_encode_options &options)
{
    return options.jpeg_subsampling == FC_JPEG_SUBSAMPLING_YUV420 ? "4:2:0" : "4:4:4";
}

fc_code encode_jpeg(const fc_image &img, const fc_encode_options &options, fc_buf *out, fc_error *err)
{
    uint32_t quality = options.quality;
    if (quality < 1 || quality > 100)
        return fc_error_set(err, FC_ERR_USAGE, "encode: JPEG quality %u outside 1..100", quality);
    std::underlying_type_t<fc_jpeg_subsampling> sampling;
    std::memcpy(&sampling, &options.jpeg_subsampling, sizeof sampling);
    if (sampling != FC_JPEG_SUBSAMPLING_YUV444 && sampling != FC_JPEG_SUBSAMPLING_YUV420)
        return fc_error_set(err, FC_ERR_USAGE, "encode: unknown JPEG subsampling %lld", (long long)sampling);
    uint32_t channels = img.channels == 4 ? 3 : img.channels;
    ImageSpec spec((int)img.width, (int)img.height, (int)channels, OIIO::TypeUInt8);
    spec.attribute("Compression", "jpeg:" + std::to_string(quality));
    if (channels == 3)
        spec.attribute("jpeg:subsampling", jpeg_sampling_name(options));
    std::vector<uint8_t> display = to_display_u8(img, channels);
    return write_in_memory("jpeg", spec, OIIO::TypeUInt8, display.data(), out, err);
}

fc_code encode_exr(const fc_image &img, fc_buf *out, fc_error *err)
{
    ImageSpec spec((int)img.width, (int)img.height, (int)img.channels, OIIO::TypeFloat);
    if (img.channels == 1) {
        /* A single-channel AOV is depth-like data: "Z" is the name EXR tools expect. */
        spec.channelnames = {"Z"};
        spec.alpha_channel = -1;
    }
    spec.attribute("compression", "zip");
    std::vector<float> linear = to_linear_f32(img);
    return write_in_memory("openexr", spec, OIIO::TypeFloat, linear.data(), out, err);
}

fc_code encode_checked(const fc_image &img, fc_image_format format, const fc_encode_options &options,
                       fc_buf *out, fc_error *err)
{
    switch (format) {
    case FC_FORMAT_PNG:
        return encode_png(img, options.png_compression, out, err);
    case FC_FORMAT_JPEG:
        return encode_jpeg(img, options, out, err);
    case FC_FORMAT_EXR:
        return encode_exr(img, out, err);
    case FC_FORMAT_RAW:
        return append_bytes(out, img.pixels, pixel_bytes(img), err);
    case FC_FORMAT_H264:
        break;   /* a video stream's frame, not a file: h264_encoder.h */
    }
    return fc_error_set(err, FC_ERR_USAGE, "encode: unknown image format %d", (int)format);
}

}  // namespace

extern "C" fc_code fc_encode_image(const fc_image *img, fc_image_format format, uint32_t quality,
                                   fc_buf *out, fc_error *err)
{
    return fc_encode_image_png_level(img, format, quality, FC_PNG_DEFAULT_COMPRESSION, out, err);
}

extern "C" fc_code fc_encode_image_png_level(const fc_image *img, fc_image_format format, uint32_t quality,
                                             uint32_t png_compression, fc_buf *out, fc_error *err)
{
    fc_encode_options options = {quality, png_compression, FC_JPEG_SUBSAMPLING_YUV444};
    return fc_encode_image_with(img, format, &options, out, err);
}

extern "C" fc_code fc_encode_image_with(const fc_image *img, fc_image_format format,
                                        const fc_encode_options *options, fc_buf *out, fc_error *err)
{
    if (!options)
        return fc_error_set(err, FC_ERR_USAGE, "encode: no options");
    if (!out)
        return fc_error_set(err, FC_ERR_USAGE, "encode: no output buffer");
    fc_code code = check_image(img, err);
    if (code != FC_OK)
        return code;
    size_t len_before = out->len;
    try {
        code = encode_checked(*img, format, *options, out, err);
    } catch (const std::bad_alloc &) {
        code = fc_error_set(err, FC_ERR_NOMEM, "encode: out of memory");
    } catch (const std::exception &e) {
        code = fc_error_set(err, FC_ERR_ENCODE, "encode: %s", e.what());
    } catch (...) {
        code = fc_error_set(err, FC_ERR_ENCODE, "encode: unknown exception");
    }
    if (code != FC_OK)
        out->len = len_before; /* never leave half a file behind */
    return code;
}
