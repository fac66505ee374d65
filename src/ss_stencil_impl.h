/* ss_stencil_impl.h — what the stencil reader's two files share (private):
 * ss_stencil.c (files, [scheme], [param], the averaging family's masks) and
 * ss_stencil_rules.c (the rule sections of the points and neighbours
 * families).  Not installed. */
#ifndef SS_STENCIL_IMPL_H
#define SS_STENCIL_IMPL_H

#include "ss_expr.h"
#include "ss_stencil.h"

/* An exact rational num/den, den > 0, in lowest terms. */
typedef struct {
  long long num, den;
} rational;

#define MAXOVER 16 /* valences one weight is given at apart (KEY@N) at most */

/* One weight of the file as read. */
typedef struct slot slot;
struct slot {
  rational w;        /* a constant weight's value */
  ss_expr *ex;       /* the weight if an expression, or NULL */
  char *etext;       /* an expression's text, for messages */
  int keyline;       /* its line */
  int nov;           /* KEY@N lines: the weight at valence ovn[i] is ov[i] */
  long ovn[MAXOVER]; /* their valences, 1..SS_AVG_NMAX, distinct */
  slot *ov[MAXOVER]; /* their values (owned; no overrides of their own) */
};

/* Families of stencil files. */
enum { FAM_AVERAGING = 0, FAM_POINTS = 1, FAM_NEIGHBOURS = 2 };

/* Rule sections (ss_stencil_rules.c): the points family's [PLACE.POINT]
 * as place * 4 + point (0..11), then the neighbours family's five, then the
 * points family's [volume.axis] (RSEC_AXIS); RKEYS keys each at most. */
#define NRSEC     18
#define RSEC_AXIS 17
#define RKEYS     SS_AXIS_KEYS

typedef struct {
  char name[64]; /* [scheme] name */
  int have_name, have_family, have_split;
  int family; /* FAM_* */
  ss_split_kind split;
  slot m[SS_NCELLTYPES][4];       /* mask weights by type and role */
  unsigned given[SS_NCELLTYPES];  /* bit r: role r given */
  int has_mask[SS_NCELLTYPES];    /* a [mask.*] section seen */
  slot rs[NRSEC][RKEYS];          /* rule sections' weights by key */
  unsigned rgiven[NRSEC];         /* bit k: key k given */
  int has_rs[NRSEC];              /* the section seen */
  int rs_order[NRSEC];            /* the sections seen, in the file's order */
  int nrs;                        /* their number */
  char msg[384];                  /* the handler's first complaint */
  int nomem;                      /* an allocation failed in the handler: the
                                     parse ends in SS_ENOMEM, whatever else */
  int msg_line;                   /* its line (1-based), 0 before any */
  const char *text;               /* the file's text, read line by line */
  const char *next;               /* where the next line starts in text */
  int line;                       /* line of the text last handed to inih */
  int newlines;                   /* newlines in text before next */
  int long_line;                  /* first line longer than inih's buffer, or 0 */
  ss_stencil_params *collect;     /* the [param] pass: parameters read here
                                     (every other section ignored); else NULL */
  ss_stencil_params own;          /* the weights pass: [param] read again here,
                                     so that its errors come in the file's order */
  const ss_stencil_params *pv;    /* the weights pass: the values substituted */
  int used[SS_STENCIL_MAXPARAMS]; /* weights that use parameter i */
} reader;

/* The values of one weight at the valences n = 1..SS_AVG_NMAX. */
typedef struct {
  double d[SS_AVG_NMAX + 1];            /* the value */
  rational q[SS_AVG_NMAX + 1];          /* the exact value, where exact[n] */
  unsigned char exact[SS_AVG_NMAX + 1]; /* 1: rational (q[n]) */
} weight_values;

/* sum += c * r, exactly; -1 on overflow. */
int ss_stencil_add_scaled(rational *sum, long long c, rational r);
/* Free what a slot holds (not the slot). */
void ss_stencil_slot_clear(slot *sl);
/* "KEY@N": KEY into base and N into *n (0 without @); -1 for a bad N. */
int ss_stencil_key_at(const char *key, char *base, size_t cap, long *n);
/* The slot a key writes: sl (n = 0) or a new override at n; NULL with
 * R->msg set. */
slot *ss_stencil_slot_for(reader *R, slot *sl, int given, long n, const char *section,
                          const char *key);
/* value with the parameters of pv substituted (caller frees); NULL without
 * memory. */
char *ss_stencil_substitute(const char *value, const ss_stencil_params *pv, int *used);
/* Read a weight written as value into *w, the parameters' values
 * substituted first; 0 with R->msg set (R->nomem when out of memory). */
int ss_stencil_weight_key(reader *R, const char *section, const char *key,
                          const char *value, slot *w);
/* The weight of a slot at every valence (ss_stencil.c). */
ss_status ss_stencil_weight_at(const slot *sl, const char *key, const char *where,
                               const char *sec, weight_values *w, int *varies,
                               ss_error *err);
/* Line of "[section]" in text, or 0. */
int ss_stencil_section_line(const char *text, const char *section);

/* A key of a rule section: -1 if section is none (the caller goes on), else
 * 1 read or 0 with R->msg set (ss_stencil_rules.c). */
int ss_stencil_rule_key(reader *R, const char *section, const char *key,
                        const char *value);
/* The scheme of a points or neighbours file from the sections read; sl is
 * [scheme]'s line.  SS_EINPUT "WHERE:LINE: ...", SS_ENOMEM. */
ss_status ss_stencil_build_rules(const reader *R, const char *text, const char *where,
                                 int sl, ss_scheme **out, ss_error *err);

#endif
