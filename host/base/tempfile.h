/* tempfile.h: temporary files that a signal cannot leave behind.
 *
 * tp2 writes its output and its pipeline cache to temporary files and
 * renames them into place. tempfile_create registers each new temporary
 * file; if SIGINT, SIGTERM or SIGHUP ends tp2 before it is renamed, the
 * handler installed by tempfile_install_handlers unlinks every registered
 * file (unlink is async-signal-safe) and the signal then ends the process
 * as it would have: the old output stays, no partial file is left. */
#ifndef TP2_TEMPFILE_H
#define TP2_TEMPFILE_H

/* Installs the handlers; a signal that was ignored (nohup) stays ignored.
 * Call once, early, before any thread exists. */
void tempfile_install_handlers(void);

/* As mkstemp: replaces the trailing XXXXXX of path in place and creates
 * that file exclusively, mode 0600, close-on-exec. The three signals are
 * blocked from creation to registration, so in a single-threaded process
 * no signal falls between the two. Returns the descriptor, or -1 with
 * errno set (EMFILE when every registration slot is taken). */
int tempfile_create(char *path);

/* Unregisters path (a name tempfile_create filled in) once it has been
 * renamed or unlinked; unknown names are ignored. */
void tempfile_forget(const char *path);

#endif
