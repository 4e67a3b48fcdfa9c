/* image_decode.cpp — the OpenImageIO side of image_decode.h. */
#include "image_decode.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>

#include "fc_error.h"

namespace {

fc_code decode(const uint8_t *data, size_t size, const char *extension, int as_float, fc_decoded_image *out,
               fc_error *err)
{
    OIIO::Filesystem::IOMemReader reader(data, size);
    std::string name = std::string("memory.") + extension;
    /* Samples exactly as stored: no premultiplication of PNG's straight alpha. */
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    /* A reader opened with a config takes its proxy from the config. */
    OIIO::Filesystem::IOProxy *proxy = &reader;
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    auto input = OIIO::ImageInput::create(name, false, &config, &reader);
    if (!input)
        return fc_error_set(err, FC_ERR_PARSE, "decode %s: %s", extension, OIIO::geterror().c_str());
    OIIO::ImageSpec spec;
    if (!input->open(name, spec, config))
        return fc_error_set(err, FC_ERR_PARSE, "decode %s: %s", extension, input->geterror().c_str());
    if (spec.nchannels < 1 || spec.nchannels > 4)
        return fc_error_set(err, FC_ERR_PARSE, "decode %s: %d channels", extension, spec.nchannels);
    out->width = (uint32_t)spec.width;
    out->height = (uint32_t)spec.height;
    out->channels = (uint32_t)spec.nchannels;
    out->as_float = as_float;
    for (int c = 0; c < spec.nchannels; c++)
        std::snprintf(out->channel_names[c], sizeof out->channel_names[c], "%s", spec.channel_name(c).c_str());
    std::snprintf(out->compression, sizeof out->compression, "%s",
                  spec.get_string_attribute("compression").c_str());
    OIIO::TypeDesc type = as_float ? OIIO::TypeFloat : OIIO::TypeUInt8;
    size_t bytes = (size_t)spec.width * spec.height * spec.nchannels * type.size();
    out->pixels = std::malloc(bytes);
    if (!out->pixels)
        return fc_error_set(err, FC_ERR_NOMEM, "decode %s: %zu bytes", extension, bytes);
    if (!input->read_image(0, 0, 0, spec.nchannels, type, out->pixels))
        return fc_error_set(err, FC_ERR_PARSE, "decode %s: %s", extension, input->geterror().c_str());
    return FC_OK;
}

}  // namespace

extern "C" fc_code fc_decode_image(const uint8_t *data, size_t size, const char *extension, int as_float,
                                   fc_decoded_image *out, fc_error *err)
{
    std::memset(out, 0, sizeof *out);
    fc_code code;
    try {
        code = decode(data, size, extension, as_float, out, err);
    } catch (const std::exception &e) {
        code = fc_error_set(err, FC_ERR_PARSE, "decode %s: %s", extension, e.what());
    }
    if (code != FC_OK)
        fc_decoded_image_free(out);
    return code;
}

extern "C" void fc_decoded_image_free(fc_decoded_image *img)
{
    std::free(img->pixels);
    std::memset(img, 0, sizeof *img);
}
