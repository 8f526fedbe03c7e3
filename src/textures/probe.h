/*
 * Internal: a probe on the texture parameter readers (mt_texparams_*), for
 * the generator of docs/REFERENCE.md: with a probe set, every lookup reports
 * the parameter's name, its type as a scene writes it, and the default the
 * creator passed, so that the reference lists what the code reads. Not
 * thread-safe; unset (NULL) in normal use.
 */
#ifndef MT_TEXTURES_PROBE_H
#define MT_TEXTURES_PROBE_H

/* choices: for a string that must be one of a list (NULL-terminated),
 * reported once more after the lookup; NULL otherwise. */
typedef void (*mt__texparams_probe_fn)(void *ctx, const char *name, const char *type, const char *def,
                                        const char *const *choices);

void mt__texparams_set_probe(mt__texparams_probe_fn fn, void *ctx);
/* Reports a lookup to the probe, when one is set. */
void mt__texparams_probe(const char *name, const char *type, const char *def, const char *const *choices);

#endif
