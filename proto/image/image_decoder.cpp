/* image_decoder.cpp — fc_decode_image_bytes over OpenImageIO.
 *
 * Readers get an in-memory IOMemReader proxy, so nothing touches the file
 * system. Every exception stops at the C boundary (fc_decode_image_bytes). */
#include "image_decoder.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <cstdlib>
#include <cstring>
#include <exception>
#include <memory>
#include <new>
#include <string>

#include "fc_error.h"

namespace {

using OIIO::ImageInput;
using OIIO::ImageSpec;
using OIIO::TypeDesc;

constexpr int RGBA = 4;

/* The formats the protocol promises. OpenImageIO would read many more, but
 * each reader is attack surface for bytes that come from the network. */
bool is_accepted_format(const char *name)
{
    return std::strcmp(name, "png") == 0 || std::strcmp(name, "jpeg") == 0 || std::strcmp(name, "openexr") == 0;
}

bool is_float_format(TypeDesc format)
{
    return format.basetype == TypeDesc::FLOAT || format.basetype == TypeDesc::HALF ||
           format.basetype == TypeDesc::DOUBLE;
}

/* Drops the message OpenImageIO keeps per thread, so a later call does not
 * report an old failure. */
void discard_oiio_error()
{
    (void)OIIO::geterror();
}

/* Opens the bytes with whichever reader recognises them: the name has no
 * extension, so every reader probes the proxy's contents. */
fc_code open_in_memory(OIIO::Filesystem::IOMemReader &reader, std::unique_ptr<ImageInput> &input, fc_error *err)
{
    ImageSpec config;
    /* Samples exactly as stored: PNG's straight alpha is not premultiplied. */
    config.attribute("oiio:UnassociatedAlpha", 1);
    OIIO::Filesystem::IOProxy *proxy = &reader;
    config.attribute("oiio:ioproxy", TypeDesc::PTR, &proxy);
    input = ImageInput::open("memory", &config, &reader);
    if (!input) {
        discard_oiio_error();
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "not a PNG, JPEG or EXR image");
    }
    if (!is_accepted_format(input->format_name()))
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "a %s image: only PNG, JPEG and EXR are accepted",
                            input->format_name());
    return FC_OK;
}

fc_code check_spec(const ImageSpec &spec, uint32_t max_side, fc_error *err)
{
    if (spec.deep)
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "a deep EXR image: only flat images are accepted");
    if (spec.width < 1 || spec.height < 1 || spec.nchannels < 1)
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "an image of %dx%d pixels and %d channels", spec.width,
                            spec.height, spec.nchannels);
    if ((uint32_t)spec.width > max_side || (uint32_t)spec.height > max_side)
        return fc_error_set(err, FC_ERR_LIMIT, "image of %dx%d pixels exceeds the limit of %u per side", spec.width,
                            spec.height, (unsigned)max_side);
    return FC_OK;
}

/* Completes n RGBA pixels of which the decoder filled the first `channels`
 * (1..4) samples: grey spreads to R, G and B, a missing alpha is opaque. */
template <typename T>
void widen_to_rgba(T *rgba, int channels, size_t n, T opaque)
{
    for (size_t i = 0; channels < RGBA && i < n; i++) {
        T *p = rgba + i * RGBA;
        if (channels < 3) {
            T alpha = channels == 2 ? p[1] : opaque;
            p[1] = p[2] = p[0];
            p[3] = alpha;
        } else {
            p[3] = opaque;
        }
    }
}

/* Decodes straight into the RGBA buffer, the samples of a pixel spaced four
 * apart, so no second copy of a large image is ever held. */
template <typename T>
fc_code read_rgba(ImageInput &input, const ImageSpec &spec, TypeDesc type, T opaque, T *pixels, fc_error *err)
{
    int channels = spec.nchannels < RGBA ? spec.nchannels : RGBA;
    if (!input.read_image(0, 0, 0, channels, type, pixels, RGBA * sizeof(T)))
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "the image data does not decode: %s",
                            input.geterror().c_str());
    widen_to_rgba(pixels, channels, (size_t)spec.width * (size_t)spec.height, opaque);
    return FC_OK;
}

fc_code decode(const uint8_t *data, size_t size, uint32_t max_side, fc_image *out, fc_error *err)
{
    OIIO::Filesystem::IOMemReader reader(data, size);
    std::unique_ptr<ImageInput> input;
    fc_code code = open_in_memory(reader, input, err);
    if (code != FC_OK)
        return code;
    const ImageSpec &spec = input->spec();
    code = check_spec(spec, max_side, err);
    if (code != FC_OK)
        return code;
    fc_pixel_type type = is_float_format(spec.format) ? FC_PIXEL_F32 : FC_PIXEL_U8;
    size_t bytes = (size_t)spec.width * (size_t)spec.height * RGBA * (type == FC_PIXEL_F32 ? sizeof(float) : 1);
    void *pixels = std::malloc(bytes);
    if (!pixels)
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for a %dx%d image", spec.width, spec.height);
    code = type == FC_PIXEL_F32
               ? read_rgba<float>(*input, spec, OIIO::TypeFloat, 1.0f, static_cast<float *>(pixels), err)
               : read_rgba<uint8_t>(*input, spec, OIIO::TypeUInt8, 255, static_cast<uint8_t *>(pixels), err);
    if (code != FC_OK) {
        std::free(pixels);
        return code;
    }
    *out = fc_image{(uint32_t)spec.width, (uint32_t)spec.height, RGBA, type, pixels, bytes};
    return FC_OK;
}

}  // namespace

extern "C" fc_code fc_decode_image_bytes(const uint8_t *data, size_t size, uint32_t max_side, fc_image *out,
                                         fc_error *err)
{
    if (!out || (!data && size > 0))
        return fc_error_set(err, FC_ERR_USAGE, "decode: missing image bytes or output");
    *out = fc_image{};
    if (size == 0)
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "an empty file is not an image");
    try {
        return decode(data, size, max_side, out, err);
    } catch (const std::bad_alloc &) {
        return fc_error_set(err, FC_ERR_NOMEM, "decode: out of memory");
    } catch (const std::exception &e) {
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "the image does not decode: %s", e.what());
    } catch (...) {
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "the image does not decode");
    }
}
