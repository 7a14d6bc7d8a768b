/* test_exr_write_faults.c — ics_exr_write never destroys what it did not create (issue: a failed
 * write used to truncate and then remove() its target, whatever it was — run as root,
 * `make-env -o /dev/full` deleted the system's /dev/full). In a scratch directory of its own:
 * - a write that fails half-way (RLIMIT_FSIZE below the file's size: EFBIG, as a full disk
 *   would) over an existing file: the previous file reads back unchanged, no temporary is left;
 * - a FIFO, a character device (a /dev/full made here with mknod, root only: skipped with the
 *   reason otherwise), a directory and a symbolic link to nothing are refused with the reason
 *   before anything is opened, and are still there afterwards, as they were;
 * - a link to a regular file is written through: the file is replaced, the link stays a link;
 * - a successful write leaves only the target in the directory. */
#define _XOPEN_SOURCE 700
#include <dirent.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include "icshadow.h"
#include "testutil.h"

static char dir[512];

static const char *at(const char *name) {
  static char buf[4][600];
  static int k;
  k = (k + 1) % 4;
  snprintf(buf[k], sizeof buf[k], "%s/%s", dir, name);
  return buf[k];
}

/* the number of entries in the scratch directory other than . and .. */
static int entries(void) {
  DIR *d = opendir(dir);
  int n = 0;
  for (struct dirent *e; d && (e = readdir(d));) n += strcmp(e->d_name, ".") && strcmp(e->d_name, "..");
  if (d) closedir(d);
  return n;
}

/* an image whose pixels do not compress (ZIP): w x h x 3 floats from a hash */
static ics_image *noise(int w, int h, unsigned seed) {
  ics_image *img;
  if (ics_image_create(&img, w, h, 3) != ICS_OK) exit(2);
  unsigned x = seed;
  for (int p = 0; p < w * h * 3; p++) x = x * 1664525u + 1013904223u, img->data[p] = (float)(x >> 8) * 0x1p-24f;
  return img;
}

static int same_image(const char *path, const ics_image *want) {
  ics_image *got = NULL;
  char msg[512];
  if (ics_exr_read(path, &got, msg, sizeof msg) != ICS_OK) return 0;
  int same = got->width == want->width && got->height == want->height && got->channels == want->channels &&
             !memcmp(got->data, want->data, sizeof(float) * (size_t)want->width * want->height * want->channels);
  ics_image_destroy(got);
  return same;
}

static void expect_refused(const char *path, const char *needle, const ics_image *img) {
  char msg[512] = "";
  ics_status st = ics_exr_write(path, img, ICS_EXR_FLOAT, msg, sizeof msg);
  CHECK(st == ICS_ERR_IO && strstr(msg, needle), "%s: status %d, message '%s' (want '%s')", path, (int)st, msg,
        needle);
}

int main(void) {
  const char *td = getenv("TMPDIR");
  snprintf(dir, sizeof dir, "%s/ics_exr_faults_XXXXXX", td && *td ? td : "/tmp");
  if (!mkdtemp(dir)) return 2;
  ics_image *a = noise(64, 48, 1), *b = noise(256, 256, 2);
  char msg[512];

  /* a write that fails half-way over an existing file */
  CHECK(ics_exr_write(at("old.exr"), a, ICS_EXR_FLOAT, msg, sizeof msg) == ICS_OK, "write: %s", msg);
  CHECK(entries() == 1, "a successful write leaves only its target (%d entries)", entries());
  struct rlimit lim, small = {65536, 65536};
  getrlimit(RLIMIT_FSIZE, &lim);
  small.rlim_max = lim.rlim_max;
  signal(SIGXFSZ, SIG_IGN);
  setrlimit(RLIMIT_FSIZE, &small);
  ics_status st = ics_exr_write(at("old.exr"), b, ICS_EXR_FLOAT, msg, sizeof msg); /* ~786 kB */
  setrlimit(RLIMIT_FSIZE, &lim);
  CHECK(st == ICS_ERR_IO, "a write past RLIMIT_FSIZE fails (status %d: %s)", (int)st, msg);
  CHECK(same_image(at("old.exr"), a), "the previous file is intact after the failed write");
  CHECK(entries() == 1, "no temporary left after the failed write (%d entries)", entries());

  /* targets that are not regular files */
  CHECK(mkfifo(at("fifo"), 0600) == 0, "mkfifo");
  expect_refused(at("fifo"), "not a regular file (a FIFO)", a);
  struct stat s;
  CHECK(lstat(at("fifo"), &s) == 0 && S_ISFIFO(s.st_mode), "the FIFO is still there");
  CHECK(mkdir(at("sub"), 0700) == 0, "mkdir");
  expect_refused(at("sub"), "not a regular file (a directory)", a);
  CHECK(lstat(at("sub"), &s) == 0 && S_ISDIR(s.st_mode), "the directory is still there");
  CHECK(symlink("nothing.exr", at("dangling")) == 0, "symlink");
  expect_refused(at("dangling"), "a symbolic link to nothing", a);
  CHECK(lstat(at("dangling"), &s) == 0 && S_ISLNK(s.st_mode) && lstat(at("nothing.exr"), &s) != 0,
        "the dangling link is still there and points to nothing");
  if (geteuid() == 0) {
    CHECK(mknod(at("full"), S_IFCHR | 0666, makedev(1, 7)) == 0, "mknod (a /dev/full of our own)");
    expect_refused(at("full"), "not a regular file (a device)", a);
    CHECK(lstat(at("full"), &s) == 0 && S_ISCHR(s.st_mode) && s.st_rdev == makedev(1, 7),
          "the device node is still there");
  } else {
    printf("SKIPPED the device node: mknod needs root\n");
  }

  /* a link to a regular file: written through */
  CHECK(symlink("old.exr", at("link")) == 0, "symlink");
  CHECK(ics_exr_write(at("link"), b, ICS_EXR_FLOAT, msg, sizeof msg) == ICS_OK, "write through a link: %s", msg);
  CHECK(lstat(at("link"), &s) == 0 && S_ISLNK(s.st_mode) && same_image(at("old.exr"), b),
        "the link stays a link, its file holds the new image");
  int want = 5 + (geteuid() == 0);
  CHECK(entries() == want, "no temporaries left: %d entries (want %d)", entries(), want);

  ics_image_destroy(a);
  ics_image_destroy(b);
  char cmd[600];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  if (system(cmd) != 0) return 1;
  return test_summary("test_exr_write_faults");
}
