/* The C side of exic_base_posix (src/exic/base/posix.f90): the POSIX calls whose arguments are
 * ABI-specific structures or macros (struct stat and S_ISREG, struct rlimit and RLIMIT_AS,
 * errno and strerror), behind plain int / long long / char* interfaces that Fortran binds
 * with bind(C). Nothing here allocates or keeps state. */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

/* What `path` is: 1 a regular file, 2 a directory, 3 something else (character or block
 * device, FIFO, socket), 0 when stat(2) fails (no such file, no permission). Symbolic links
 * are followed. */
int exic_c_file_kind(const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0) return 0;
    if (S_ISREG(st.st_mode)) return 1;
    if (S_ISDIR(st.st_mode)) return 2;
    return 3;
}

/* mkdir(path, 0777) (the umask applies). Returns 0 on success, else errno, with the system's
 * text for it in msg (at most msglen bytes, NUL-terminated). */
int exic_c_mkdir(const char *path, char *msg, int msglen)
{
    int e;
    if (mkdir(path, 0777) == 0) return 0;
    e = errno;
    if (msglen > 0) snprintf(msg, (size_t)msglen, "%s", strerror(e));
    return e;
}

/* The soft limit of the address space (RLIMIT_AS) in bytes in *bytes, -1 when unlimited.
 * Returns 0 on success, -1 when getrlimit(2) fails. */
int exic_c_address_space_limit(long long *bytes)
{
    struct rlimit rl;
    if (getrlimit(RLIMIT_AS, &rl) != 0) return -1;
    if (rl.rlim_cur == RLIM_INFINITY || rl.rlim_cur > (rlim_t)9223372036854775807LL) {
        *bytes = -1;
    } else {
        *bytes = (long long)rl.rlim_cur;
    }
    return 0;
}

/* Cut the file `path` to `size` bytes (truncate(2)). Returns 0 or errno. */
int exic_c_truncate(const char *path, long long size)
{
    if (truncate(path, (off_t)size) == 0) return 0;
    return errno;
}

/* The size of `path` in bytes, -1 when stat(2) fails. */
long long exic_c_file_size(const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0) return -1;
    return (long long)st.st_size;
}

/* Copy the bytes of the file `from` to `to` (created or truncated, mode 0666 less the umask)
 * with read(2) and write(2) in 1 MiB blocks, short writes and EINTR handled, and close both.
 * (copy_file_range(2) was tried: on ext4 its in-kernel page copy took 3.5 times the processor
 * time of read/write on the field file of the seed's 7.2, doc/performance.md section 6.5.)
 * Returns 0, or errno with the system's text and the failing step in msg (at most msglen
 * bytes, NUL-terminated). */
int exic_c_copy_file(const char *from, const char *to, char *msg, int msglen)
{
    enum { BLOCK = 1 << 20 };
    static char buf[BLOCK];
    const char *what = "open";
    const char *which = from;
    int in, out, e = 0;
    in = open(from, O_RDONLY);
    if (in < 0) {
        e = errno;
        goto done;
    }
    which = to;
    out = open(to, O_WRONLY | O_CREAT | O_TRUNC, 0666);
    if (out < 0) {
        e = errno;
        close(in);
        goto done;
    }
    for (;;) {
        ssize_t n = read(in, buf, BLOCK);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) {
            e = errno;
            what = "read";
            which = from;
            break;
        }
        if (n == 0) break;
        for (ssize_t done = 0; done < n;) {
            ssize_t w = write(out, buf + done, (size_t)(n - done));
            if (w < 0 && errno == EINTR) continue;
            if (w < 0) {
                e = errno;
                what = "write";
                break;
            }
            done += w;
        }
        if (e != 0) break;
    }
    close(in);
    if (close(out) != 0 && e == 0) {
        e = errno;
        what = "close";
        which = to;
    }
done:
    if (e != 0 && msglen > 0) snprintf(msg, (size_t)msglen, "cannot %s '%s': %s", what, which, strerror(e));
    return e;
}

/* Flush the C streams and end the process with `code` without running the exit handlers
 * (_exit(2)): after a failed write, HDF5's own handler would try again to flush the file it
 * could not close, and crash. */
void exic_c_exit_now(int code)
{
    fflush(NULL);
    _exit(code);
}
