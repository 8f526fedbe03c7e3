/* Internal: statements given as text, applied to a graphics state, for the
 * material and texture entry points that take text. */
#ifndef MT_PARAMS_STATE_TEXT_H
#define MT_PARAMS_STATE_TEXT_H

#include "materia/state.h"

/* What the text held: its Material and NamedMaterial statements, and its
 * last Texture statement's name and namespace. */
typedef struct mt__text_summary {
    int materials; /* Material and NamedMaterial statements */
    int textures;  /* Texture statements */
    char texture[256];
    int texture_is_float;
} mt__text_summary;

/* mt_state_apply_text, filling *sum (may be NULL). */
mt_status mt__state_apply_text(mt_state *s, const char *text, mt__text_summary *sum, mt_error *err);

/* The state's warning callback (NULL when none). */
mt_warning_fn mt__state_warning(const mt_state *s, void **ctx);

#endif
