/* Video output: raw RGBA frames piped into Debian's ffmpeg, which encodes
 * them by the file's extension. pelt links no codec library; without
 * ffmpeg the message says what to install and that PNG sequences work. */
#include "apps/video.h"

#include "apps/cli.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

extern char **environ;

typedef struct video_format {
    const char *ext;   /* with the dot */
    const char *muxer; /* ffmpeg -f */
    const char *codec_args[14]; /* NULL-terminated */
} video_format;

/* H.264 and VP9 in 4:2:0 need even sizes: an odd width or height is padded
 * by one row or column of black. A GIF gets a palette made from its own
 * frames. */
#define EVEN "pad=ceil(iw/2)*2:ceil(ih/2)*2"
static const video_format formats[] = {
    {".mp4", "mp4",
     {"-vf", EVEN, "-c:v", "libx264", "-pix_fmt", "yuv420p", "-crf", "20", "-movflags",
      "+faststart", NULL}},
    {".webm", "webm",
     {"-vf", EVEN, "-c:v", "libvpx-vp9", "-pix_fmt", "yuv420p", "-crf", "32", "-b:v", "0",
      "-row-mt", "1"}},
    {".gif", "gif", {"-vf", "split[a][b];[a]palettegen[p];[b][p]paletteuse", NULL}},
};
#define FORMAT_COUNT (sizeof formats / sizeof formats[0])

static const video_format *format_of(const char *path)
{
    const char *dot = strrchr(path, '.');
    if (!dot || strchr(dot, '/')) return NULL;
    for (size_t i = 0; i < FORMAT_COUNT; i++) {
        const char *a = dot, *b = formats[i].ext;
        while (*a && *b && (*a | 0x20) == *b) a++, b++; /* ASCII, any case */
        if (!*a && !*b) return &formats[i];
    }
    return NULL;
}

bool cli_video_is_video(const char *path) { return format_of(path) != NULL; }

/* The first executable `name` on PATH, as execvp would find it. */
static bool find_in_path(const char *name, char *out, size_t size)
{
    const char *path = getenv("PATH");
    if (!path) path = "/usr/local/bin:/usr/bin:/bin";
    for (const char *p = path;; p++) {
        const char *end = strchr(p, ':');
        size_t len = end ? (size_t)(end - p) : strlen(p);
        int n = len ? snprintf(out, size, "%.*s/%s", (int)len, p, name)
                    : snprintf(out, size, "./%s", name);
        if (n > 0 && (size_t)n < size && access(out, X_OK) == 0) return true;
        if (!end) return false;
        p = end;
    }
}

bool cli_video_check(const char *cmd, const char *path, char *ffmpeg, size_t ffmpeg_size)
{
    if (find_in_path("ffmpeg", ffmpeg, ffmpeg_size)) return true;
    const char *dot = strrchr(path, '.');
    int stem = dot ? (int)(dot - path) : (int)strlen(path);
    cli_error(cmd,
              "writing the video '%s' needs ffmpeg, which is not installed (not found on PATH).\n"
              "  Install it (Debian: sudo apt-get install ffmpeg), or write a PNG sequence\n"
              "  instead: -o %.*s_%%04d.png",
              path, stem, path);
    return false;
}

bool cli_video_open(const char *cmd, const char *ffmpeg, const char *path, unsigned width,
                    unsigned height, float fps, cli_video *v)
{
    memset(v, 0, sizeof *v);
    v->fd = -1;
    v->cmd = cmd;
    v->path = path;
    v->frame_bytes = (size_t)width * height * 4;
    const video_format *f = format_of(path);
    if (!f) {
        cli_error(cmd, "-o '%s': not a video file (.mp4, .webm, .gif)", path);
        return false;
    }
    /* Fail on an unwritable name here, with its own message, rather than
     * after ffmpeg has been given every frame. */
    FILE *probe = fopen(path, "wb");
    if (!probe) {
        cli_error(cmd, "cannot write '%s': %s", path, strerror(errno));
        return false;
    }
    fclose(probe);

    char size[32], rate[32], out[4096 + 8];
    snprintf(size, sizeof size, "%ux%u", width, height);
    snprintf(rate, sizeof rate, "%.6g", (double)fps);
    if (snprintf(out, sizeof out, "file:%s", path) >= (int)sizeof out) {
        cli_error(cmd, "-o '%.60s...': path too long", path);
        remove(path);
        return false;
    }
    /* "file:" keeps a name starting with '-' a file name. */
    const char *argv[48] = {"ffmpeg", "-hide_banner", "-loglevel", "error", "-nostats", "-y",
                            "-f", "rawvideo", "-pix_fmt", "rgba", "-video_size", size,
                            "-framerate", rate, "-i", "pipe:0", "-an"};
    size_t n = 17;
    for (size_t i = 0; f->codec_args[i]; i++) argv[n++] = f->codec_args[i];
    argv[n++] = "-f";
    argv[n++] = f->muxer;
    argv[n++] = out;
    argv[n] = NULL;

    int fds[2];
    if (pipe(fds) != 0) {
        cli_error(cmd, "cannot make a pipe to ffmpeg: %s", strerror(errno));
        remove(path);
        return false;
    }
    /* Only ffmpeg's stdin stays open in ffmpeg: close-on-exec for both
     * ends, dup2 onto 0 clears the flag on the copy. */
    fcntl(fds[0], F_SETFD, FD_CLOEXEC);
    fcntl(fds[1], F_SETFD, FD_CLOEXEC);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, fds[0], 0);
    pid_t pid;
    int err = posix_spawn(&pid, ffmpeg, &actions, NULL, (char *const *)argv, environ);
    posix_spawn_file_actions_destroy(&actions);
    close(fds[0]);
    if (err) {
        cli_error(cmd, "cannot run %s: %s", ffmpeg, strerror(err));
        close(fds[1]);
        remove(path);
        return false;
    }
    /* ffmpeg exiting early must not kill pelt with SIGPIPE: the write
     * fails with EPIPE and close reports ffmpeg's status. */
    signal(SIGPIPE, SIG_IGN);
    v->pid = pid;
    v->fd = fds[1];
    return true;
}

bool cli_video_write(cli_video *v, const uint8_t *rgba)
{
    const uint8_t *p = rgba;
    size_t left = v->frame_bytes;
    while (left > 0) {
        ssize_t w = write(v->fd, p, left);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) {
            v->failed = true;
            return false;
        }
        p += w;
        left -= (size_t)w;
    }
    v->frames++;
    return true;
}

bool cli_video_close(cli_video *v)
{
    if (v->fd < 0) return false;
    close(v->fd);
    v->fd = -1;
    int status = 0;
    pid_t r;
    while ((r = waitpid(v->pid, &status, 0)) < 0 && errno == EINTR) {
    }
    bool exited = r == v->pid && WIFEXITED(status);
    if (exited && WEXITSTATUS(status) == 0 && !v->failed) return true;
    if (exited && WEXITSTATUS(status) != 0)
        cli_error(v->cmd, "ffmpeg failed writing '%s' (exit status %d; its message is above)",
                  v->path, WEXITSTATUS(status));
    else if (r == v->pid && WIFSIGNALED(status))
        cli_error(v->cmd, "ffmpeg was killed by signal %d writing '%s'", WTERMSIG(status), v->path);
    else
        cli_error(v->cmd, "ffmpeg stopped reading the frames of '%s' after %u", v->path, v->frames);
    remove(v->path);
    return false;
}
