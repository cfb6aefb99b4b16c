/* The page's fixed texts, included whole from their files by the
 * assembler's .incbin (ELF targets: GCC and Clang on Linux), each followed
 * by a NUL byte. The file paths come from CMake (core/CMakeLists.txt),
 * which also makes this file depend on them. */
#include <stddef.h>

#include "vbp_assets.h"

#define VBP_STR2(x) #x
#define VBP_STR(x) VBP_STR2(x)

/* Defines the byte array `sym` holding the file at `path` and a NUL. */
#define VBP_EMBED(sym, path)                                                                        \
    __asm__(".section .rodata\n"                                                                   \
            ".global " #sym "\n"                                                                   \
            ".hidden " #sym "\n"                                                                   \
            ".type " #sym ", @object\n"                                                            \
            ".balign 16\n" #sym ":\n"                                                              \
            ".incbin \"" path "\"\n"                                                               \
            ".byte 0\n"                                                                            \
            ".previous\n");                                                                        \
    extern const char sym[]

VBP_EMBED(vbp_page_js_text, VBP_STR(VBP_PAGE_DIR) "/page_view.js");
VBP_EMBED(vbp_page_css_text, VBP_STR(VBP_PAGE_DIR) "/page.css");
VBP_EMBED(vbp_page_body_text, VBP_STR(VBP_PAGE_DIR) "/page_body.html");

#ifdef VBP_NGL_JS
VBP_EMBED(vbp_ngl_js_text, VBP_STR(VBP_NGL_JS));
const char *vbp_viewer_js(void)
{
    return vbp_ngl_js_text;
}
#else
const char *vbp_viewer_js(void)
{
    return NULL;
}
#endif

const char *vbp_page_js(void)
{
    return vbp_page_js_text;
}

const char *vbp_page_css(void)
{
    return vbp_page_css_text;
}

const char *vbp_page_body(void)
{
    return vbp_page_body_text;
}
