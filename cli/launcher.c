/* demlight: the command users run. It is a small program of its own, linked with the C library
 * alone, so that it starts at once: it holds SIGINT, SIGTERM and SIGHUP (blocks them), then
 * runs the real program, demlight-core in its own folder, in its place (execv). A blocked
 * signal's mask survives execv, so a signal that comes while demlight-core loads its many shared
 * libraries stays pending until demlight-core has installed its handlers, and is then answered
 * as one (cli/main.cpp, demlight/geo/signals.h): the process ends with exit 130, not killed by the
 * signal. DEMLIGHT_SIGNALS_HELD tells demlight-core which of them it should release (those this
 * program blocked; one its caller blocked stays blocked). */
#include <errno.h>
#include <limits.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

int main(int argc, char** argv) {
    (void)argc;
    sigset_t held, before;
    sigemptyset(&held);
    sigaddset(&held, SIGINT);
    sigaddset(&held, SIGTERM);
    sigaddset(&held, SIGHUP);
    sigprocmask(SIG_BLOCK, &held, &before);
    char released[16] = "";
    if (!sigismember(&before, SIGINT)) strcat(released, "I");
    if (!sigismember(&before, SIGTERM)) strcat(released, "T");
    if (!sigismember(&before, SIGHUP)) strcat(released, "H");
    setenv("DEMLIGHT_SIGNALS_HELD", released, 1);

    char self[PATH_MAX];
    const ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
    if (n <= 0) {
        fprintf(stderr, "demlight: internal error: cannot find this program's folder (/proc/self/exe: %s)\n",
                strerror(errno));
        return 3;
    }
    self[n] = '\0';
    char* slash = strrchr(self, '/');
    static const char kCore[] = "/demlight-core";
    if (!slash || (size_t)(slash - self) + sizeof kCore > sizeof self) {
        fprintf(stderr, "demlight: internal error: this program's path is too long\n");
        return 3;
    }
    strcpy(slash, kCore);
    execv(self, argv);
    fprintf(stderr, "demlight: internal error: cannot run %s (%s); it is installed beside demlight\n", self,
            strerror(errno));
    return 3;
}
