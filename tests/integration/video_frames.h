/* video_frames.h — decodes every frame of a video file with libavformat and
 * libavcodec into RGB8, so the render tests check the video the CLI wrote
 * with the library players use rather than with the code under test. */
#ifndef FC_TEST_VIDEO_FRAMES_H
#define FC_TEST_VIDEO_FRAMES_H

#include <stdbool.h>
#include <stdint.h>

#define VIDEO_FRAMES_MAX 64

typedef struct video_frames {
    uint32_t width, height;
    uint32_t count;                    /* frames decoded, in presentation order */
    uint8_t *rgb[VIDEO_FRAMES_MAX];    /* width * height * 3 bytes each, rows top to bottom */
    char codec[32];                    /* the decoder's name, e.g. "h264", "vp9" */
} video_frames;

/* false (with a reason on stderr) when the file does not open or decode. */
bool video_frames_read(const char *path, video_frames *out);
void video_frames_free(video_frames *v);

#endif
