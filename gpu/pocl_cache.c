/* PoCL's kernel cache, checked before PoCL reads it. PoCL caches each
 * program it builds (POCL_KERNEL_CACHE, on by default) as
 *   <cache>/<2 letters>/<hash>/program.bc              the program's LLVM bitcode
 *   <cache>/<2 letters>/<hash>/<kernel>/<wg>/<kernel>.so  each kernel, compiled
 * and trusts those files: a bitcode file cut short or of garbage aborts the
 * process (an assertion in pocl_llvm_build_program, exit 134), half a .so
 * is mapped and faults (SIGBUS, 135), an empty program.bc makes every build
 * fail (the commands fall back to the reference backend, run after run).
 * vorball's own cache survives all of these (runtime.c); this file gives
 * PoCL's the same footing: before the first OpenCL call of a process,
 * every program.bc (and any *.bc) must be whole LLVM bitcode - its
 * top-level blocks, each with its length, end exactly at the end of the
 * file - and every .so a whole ELF file - its program and section headers,
 * and the bytes they describe, inside the file. A program folder holding a
 * file that is not is removed (warning W750), so PoCL builds it again from
 * source. PoCL writes each file under a temporary name and renames it, so a
 * file under its final name is never one being written by a concurrent
 * process. What these checks cannot see (bytes changed inside a file of
 * the right shape) they do not claim to.
 *
 * Without POCL_CACHE_DIR in the environment, vorball points PoCL at its
 * own folder, <vorball's cache>/pocl, so it never removes anything from a
 * cache that other programs use; with it, the folder named is checked. */
#define _DEFAULT_SOURCE /* d_type's DT_ names (dirent.h) */
#include "vbg_runtime.h"
#include "vb_diag.h"

#include <dirent.h>
#include <elf.h>
#include <errno.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

/* Reads n bytes at offset off of f; 0 on success. */
static int read_at(FILE *f, long off, void *buf, size_t n)
{
    return fseek(f, off, SEEK_SET) != 0 || fread(buf, 1, n, f) != n ? -1 : 0;
}

/* Bits of an LLVM bitstream, read as LLVM does: little-endian 32-bit words,
 * least significant bit first. */
typedef struct {
    FILE *f;
    uint64_t size, pos; /* bytes; pos: the word being read */
    uint32_t word;
    unsigned used;      /* bits of word consumed */
} bits;

static int bits_read(bits *b, unsigned n, uint32_t *out)
{
    *out = 0;
    for (unsigned k = 0; k < n; k++) {
        if (b->used == 32) {
            unsigned char w[4];
            if (b->pos + 4 > b->size || read_at(b->f, (long)b->pos, w, 4) != 0)
                return -1;
            b->word = (uint32_t)w[0] | (uint32_t)w[1] << 8 | (uint32_t)w[2] << 16 |
                      (uint32_t)w[3] << 24;
            b->pos += 4;
            b->used = 0;
        }
        *out |= ((b->word >> b->used++) & 1u) << k;
    }
    return 0;
}

/* A variable-width value of n-bit chunks (the top bit of each: more). */
static int bits_vbr(bits *b, unsigned n, uint32_t *out)
{
    uint32_t chunk, v = 0;
    for (unsigned shift = 0; shift < 32; shift += n - 1) {
        if (bits_read(b, n, &chunk) != 0)
            return -1;
        v |= (chunk & ((1u << (n - 1)) - 1)) << shift;
        if (!(chunk >> (n - 1))) {
            *out = v;
            return 0;
        }
    }
    return -1;
}

/* NULL when the file is whole LLVM bitcode, else what is wrong. At the
 * top level a bitcode file is a sequence of blocks, each announced by
 * ENTER_SUBBLOCK (abbreviation 1 in 2 bits), its id (vbr8), its
 * abbreviation width (vbr4), alignment to 32 bits and its length in words;
 * their lengths must add up to the file exactly. */
static const char *bitcode_damage(FILE *f, uint64_t size)
{
    unsigned char magic[4];
    if (size == 0)
        return "empty";
    if (size < 8 || read_at(f, 0, magic, 4) != 0 || memcmp(magic, "BC\xc0\xde", 4) != 0)
        return "not LLVM bitcode";
    bits b = {f, size, 4, 0, 32};
    int blocks = 0;
    while (b.pos < size) {
        uint32_t abbrev, id, width, len;
        if (bits_read(&b, 2, &abbrev) != 0 || abbrev != 1 || bits_vbr(&b, 8, &id) != 0 ||
            bits_vbr(&b, 4, &width) != 0)
            return "a top-level bitcode block is malformed";
        b.used = 32; /* align to the next word: the block's length */
        if (bits_read(&b, 32, &len) != 0)
            return "cut short (a block's header runs past the end)";
        if ((uint64_t)len * 4 > size - b.pos)
            return "cut short (a block runs past the end)";
        b.pos += (uint64_t)len * 4;
        blocks++;
    }
    return blocks ? NULL : "no bitcode block";
}

/* NULL when the ELF file's headers and the bytes they describe lie inside
 * the file, else what is wrong. */
static const char *elf_damage(FILE *f, uint64_t size)
{
    unsigned char id[EI_NIDENT];
    if (size == 0)
        return "empty";
    if (size < sizeof(Elf64_Ehdr) || read_at(f, 0, id, sizeof id) != 0 ||
        memcmp(id, ELFMAG, SELFMAG) != 0 || id[EI_CLASS] != ELFCLASS64)
        return "not a 64-bit ELF file";
    Elf64_Ehdr h;
    if (read_at(f, 0, &h, sizeof h) != 0)
        return "cannot read it";
    if (h.e_phnum && (h.e_phentsize != sizeof(Elf64_Phdr) ||
                      h.e_phoff + (uint64_t)h.e_phnum * sizeof(Elf64_Phdr) > size))
        return "cut short (program headers past the end)";
    if (h.e_shnum && (h.e_shentsize != sizeof(Elf64_Shdr) ||
                      h.e_shoff + (uint64_t)h.e_shnum * sizeof(Elf64_Shdr) > size))
        return "cut short (section headers past the end)";
    for (unsigned k = 0; k < h.e_phnum; k++) {
        Elf64_Phdr p;
        if (read_at(f, (long)(h.e_phoff + k * sizeof p), &p, sizeof p) != 0 ||
            p.p_offset + p.p_filesz > size)
            return "cut short (a segment runs past the end)";
    }
    for (unsigned k = 0; k < h.e_shnum; k++) {
        Elf64_Shdr s;
        if (read_at(f, (long)(h.e_shoff + k * sizeof s), &s, sizeof s) != 0 ||
            (s.sh_type != SHT_NOBITS && s.sh_offset + s.sh_size > size))
            return "cut short (a section runs past the end)";
    }
    return NULL;
}

static int ends_with(const char *s, const char *tail)
{
    size_t n = strlen(s), k = strlen(tail);
    return n >= k && strcmp(s + n - k, tail) == 0;
}

/* The first damaged file under dir (depth levels down at most) into bad,
 * with why; 1 when one was found. */
static int find_damage(const char *dir, int depth, char *bad, size_t cap, const char **why)
{
    DIR *d = opendir(dir);
    if (!d)
        return 0;
    int found = 0;
    for (struct dirent *e; !found && (e = readdir(d));) {
        if (e->d_name[0] == '.')
            continue;
        char path[4096];
        if (snprintf(path, sizeof path, "%s/%s", dir, e->d_name) >= (int)sizeof path)
            continue;
        struct stat st;
        if (lstat(path, &st) != 0)
            continue;
        if (S_ISDIR(st.st_mode)) {
            if (depth > 0)
                found = find_damage(path, depth - 1, bad, cap, why);
            continue;
        }
        int bc = ends_with(e->d_name, ".bc"), so = ends_with(e->d_name, ".so");
        if (!S_ISREG(st.st_mode) || (!bc && !so))
            continue;
        FILE *f = fopen(path, "rb");
        if (!f)
            continue; /* removed meanwhile, or not ours to read */
        *why = bc ? bitcode_damage(f, (uint64_t)st.st_size) : elf_damage(f, (uint64_t)st.st_size);
        fclose(f);
        if (*why) {
            snprintf(bad, cap, "%s", path);
            found = 1;
        }
    }
    closedir(d);
    return found;
}

/* Removes dir and everything under it (no symbolic link is followed);
 * 0 when it is gone. */
static int remove_tree(const char *dir)
{
    DIR *d = opendir(dir);
    if (d) {
        for (struct dirent *e; (e = readdir(d));) {
            if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
                continue;
            char path[4096];
            if (snprintf(path, sizeof path, "%s/%s", dir, e->d_name) >= (int)sizeof path)
                continue;
            struct stat st;
            if (lstat(path, &st) == 0 && S_ISDIR(st.st_mode))
                remove_tree(path);
            else
                unlink(path);
        }
        closedir(d);
    }
    return rmdir(dir) == 0 || errno == ENOENT ? 0 : -1;
}

/* PoCL 2.10 leaves an empty tempfile_* in the cache folder's root in every
 * process (a name it makes and never uses), and each one cost this check an
 * opendir: 6,000 of them after a day of runs on the build machine. In
 * vorball's own folder (own) those empty for an hour are removed: PoCL
 * writes a file and renames it within the same build, so none of them is
 * in use. */
static void drop_leftover(const char *root, const char *name, int own)
{
    char path[4096];
    struct stat st;
    if (!own || strncmp(name, "tempfile_", 9) != 0 ||
        snprintf(path, sizeof path, "%s/%s", root, name) >= (int)sizeof path ||
        lstat(path, &st) != 0 || !S_ISREG(st.st_mode) || st.st_size != 0 ||
        time(NULL) - st.st_mtime < 3600)
        return;
    unlink(path);
}

/* Checks each program folder <root>/<2 letters>/<hash>: removes those that
 * hold a damaged file, with warning W750; own: root is vorball's own
 * folder (drop_leftover). */
static void check_root(vb_ctx *ctx, const char *root, int own)
{
    DIR *d = opendir(root);
    if (!d)
        return;
    for (struct dirent *e; (e = readdir(d));) {
        if (e->d_name[0] == '.')
            continue;
        if (e->d_type != DT_DIR && e->d_type != DT_UNKNOWN) {
            drop_leftover(root, e->d_name, own);
            continue;
        }
        char group[4096];
        if (snprintf(group, sizeof group, "%s/%s", root, e->d_name) >= (int)sizeof group)
            continue;
        DIR *g = opendir(group);
        if (!g)
            continue; /* a temporary file of PoCL's, or anything else */
        for (struct dirent *p; (p = readdir(g));) {
            if (p->d_name[0] == '.')
                continue;
            char prog[4096], bad[4096];
            const char *why = NULL;
            if (snprintf(prog, sizeof prog, "%s/%s", group, p->d_name) >= (int)sizeof prog ||
                !find_damage(prog, 3, bad, sizeof bad, &why))
                continue;
            int gone = remove_tree(prog) == 0;
            vb_warn(ctx, VB_W_PROGRAM_CACHE_BAD, bad, 0,
                    "PoCL's cached program cannot be used (%s): %s, rebuilt from source", why,
                    gone ? "its folder removed" : "its folder could not be removed");
        }
        closedir(g);
    }
    closedir(d);
}

void vbg_pocl_cache_check(vb_ctx *ctx)
{
    /* Once per process: PoCL reads its cache folder when it starts. */
    static atomic_int done;
    if (atomic_exchange(&done, 1))
        return;
    const char *kc = getenv("POCL_KERNEL_CACHE");
    if (kc && strcmp(kc, "0") == 0)
        return;
    const char *root = getenv("POCL_CACHE_DIR");
    char own[900];
    int ours = !root || !*root;
    if (ours) {
        if (!vbg_cache_dir(own, sizeof own - 6, 1))
            return;
        strcat(own, "/pocl");
        if (mkdir(own, 0755) != 0 && errno != EEXIST)
            return;
        setenv("POCL_CACHE_DIR", own, 1);
        root = own;
    }
    check_root(ctx, root, ours);
}
