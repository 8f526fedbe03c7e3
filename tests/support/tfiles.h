/*
 * Temporary files for tests that read scene or data files: a private
 * directory under $TMPDIR (or /tmp), files written into it, and its removal.
 */
#ifndef MT_TEST_TFILES_H
#define MT_TEST_TFILES_H

#include <stddef.h>

/* Creates a new empty directory; returns its path (static storage, one at a
 * time) or NULL. */
const char *t_tmpdir_create(const char *tag);
/* dir/name in the directory t_tmpdir_create made (static storage: eight
 * buffers used in turn, so that a call may take several such paths). */
const char *t_tmp_path(const char *name);
/* Removes the directory t_tmpdir_create made, with everything in it. */
void t_tmpdir_remove(void);
/* Writes len bytes (len = (size_t)-1: strlen(text)) to dir/rel, creating the
 * subdirectories rel names; returns the full path (static, overwritten by the
 * next call) or NULL. */
const char *t_write_file(const char *rel, const char *text, size_t len);

#endif
