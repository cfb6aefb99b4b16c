/* The fixed parts of the results page, embedded in the library at build
 * time (page_assets.c): the viewer (NGL, when the build has it), the page's
 * own script, style and body. Internal to core/page. */
#ifndef VBP_ASSETS_H
#define VBP_ASSETS_H

/* The viewer's script as a NUL-terminated text, or NULL when this build
 * was configured without it (VORBALL_NGL_JS). */
const char *vbp_viewer_js(void);

/* The page's own script (page_view.js), style (page.css) and body markup
 * (page_body.html), NUL-terminated. */
const char *vbp_page_js(void);
const char *vbp_page_css(void);
const char *vbp_page_body(void);

#endif
