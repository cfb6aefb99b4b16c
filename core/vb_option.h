/* An option declared once (geogram's CmdLine::declare_arg): its spellings,
 * value type, range, default and help in one row of a table that a command
 * parses its line with and prints as its --help, and that a binding reads
 * for its keywords (the channel analysis's table, core/discrete/
 * channel_options.c, read through lib/vb_channels.h). Plain data. */
#ifndef VB_OPTION_H
#define VB_OPTION_H

enum vb_opt_type {
    VB_OPT_FLAG,   /* no value: present sets it */
    VB_OPT_REAL,   /* a number in [min, max] */
    VB_OPT_COUNT,  /* an integer in [min, max] */
    VB_OPT_POW2,   /* a power of two in [min, max] */
    VB_OPT_PATH,   /* a file name */
    VB_OPT_CHOICE, /* one of the words in `choices` (comma-separated) */
    VB_OPT_VEC3,   /* X,Y,Z: three numbers of magnitude at most 1e6 */
    VB_OPT_FRAMES, /* A:B:S, each part optional */
    VB_OPT_NAMES   /* NAME,NAME,...: a bounded number of names */
};

typedef struct vb_option {
    int id;               /* the table's own number for the option */
    const char *name;     /* "--probe" */
    const char *alias;    /* a second spelling ("--centrelines"), or NULL */
    const char *py;       /* the Python keyword, or NULL (an output of the command) */
    int type;             /* enum vb_opt_type */
    double min, max;      /* REAL, COUNT, POW2 */
    const char *choices;  /* CHOICE: the words, comma-separated */
    const char *value;    /* the value's name in --help ("R", "FILE") */
    const char *def;      /* the default as text (NULL: none, the flag unset) */
    const char *help;     /* one paragraph; --help wraps it */
    int section;          /* where --help lists it (the table's sections) */
} vb_option;

#endif
