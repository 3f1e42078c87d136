/* pelt render -o out.mp4 / .webm / .gif: frames piped into ffmpeg. */
#ifndef PELT_APPS_VIDEO_H
#define PELT_APPS_VIDEO_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <sys/types.h>

typedef struct cli_video {
    const char *cmd, *path;
    pid_t pid;            /* ffmpeg */
    int fd;               /* its stdin */
    size_t frame_bytes;   /* width * height * 4 */
    unsigned frames;      /* written so far */
    bool failed;          /* a write failed: ffmpeg stopped reading */
} cli_video;

/* True when the name ends in an extension pelt writes as a video (.mp4,
 * .webm, .gif; any case). */
bool cli_video_is_video(const char *path);

/* Finds ffmpeg on PATH (its path into `ffmpeg`); without it, prints what
 * to install and that a PNG sequence works, and returns false. */
bool cli_video_check(const char *cmd, const char *path, char *ffmpeg, size_t ffmpeg_size);

/* Starts ffmpeg writing `path` from RGBA8 frames (rows top first) of
 * width x height at fps. Prints the error and returns false on failure
 * (an unwritable name, no pipe, ffmpeg cannot start). */
bool cli_video_open(const char *cmd, const char *ffmpeg, const char *path, unsigned width,
                    unsigned height, float fps, cli_video *v);

/* Writes one frame (width * height * 4 bytes) into the pipe; no
 * allocation. False when ffmpeg stopped reading; cli_video_close says why. */
bool cli_video_write(cli_video *v, const uint8_t *rgba);

/* Ends the stream and waits for ffmpeg. True when every frame was written
 * and ffmpeg succeeded; otherwise prints what failed, removes the file and
 * returns false. */
bool cli_video_close(cli_video *v);

#endif
