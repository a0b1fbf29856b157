/* dicom.h -- a small DICOM Part 10 reader: a data set as a tree of elements.
 *
 * What it reads (PS3.10 file format, PS3.5 encodings): files with or without
 * the 128-byte preamble and "DICM", with or without the file meta group
 * (group 0002, explicit VR little endian, or implicit where its first element
 * has no VR; its group length is not trusted); data sets in Implicit VR Little Endian or Explicit VR Little
 * Endian (also the compressed-pixel syntaxes, whose data sets are explicit VR
 * LE).  Big endian, deflated and unknown transfer syntaxes are refused, naming
 * the UID.  Without a meta group the encoding is guessed as pydicom does:
 * explicit if bytes 4-5 of the first element are two uppercase letters.
 *
 * Sequences, items and UN elements may have defined or undefined lengths
 * (PS3.5 7.5); an UN element of undefined length is read as a sequence in
 * implicit VR (PS3.5 6.2.2).  Implicit VR does not say which elements are
 * sequences: the caller names the sequences it needs (`descend`), and every
 * other element with a defined length is skipped by its length (in explicit
 * VR too).  Elements of undefined length are always walked, to find their
 * end.  Every length is checked against the end of its parent; sequences may
 * nest at most DICOM_MAX_DEPTH deep.  Every error is one line
 * "NAME: byte N: what is wrong (value)". */
#ifndef DICOM_H
#define DICOM_H

#include <stddef.h>
#include <stdint.h>

typedef struct dicom dicom;

#define DICOM_TAG(g, e) ((uint32_t)(g) << 16 | (uint32_t)(e))
#define DICOM_ITEM DICOM_TAG(0xFFFE, 0xE000)

enum { DICOM_MAX_DEPTH = 16 };   /* sequences inside sequences, at most */
enum { DICOM_ROOT = 0 };          /* the node of the whole data set */

/* 1 if buf looks like DICOM: "DICM" at byte 128, or data that starts with an
 * element of group 0002 or 0008 (a data set without preamble). */
int dicom_sniff(const unsigned char *buf, size_t len);
/* The same for the file at path (0 for "-", or a file that cannot be read). */
int dicom_sniff_file(const char *path);

/* Parse buf[0..len-1] (`name` is used in messages).  descend[0..ndescend-1]
 * are the tags of the sequences to read into; others are skipped.  buf must
 * outlive the handle (it is not copied).  Returns the handle, or NULL with
 * "NAME: byte N: ..." in err. */
dicom *dicom_parse(const unsigned char *buf, size_t len, const char *name,
                   const uint32_t *descend, int ndescend, char *err, size_t errlen);
void dicom_free(dicom *d);

/* The transfer syntax UID from the meta group ("" when there was none and the
 * encoding was guessed), and whether the data set is explicit VR. */
const char *dicom_transfer_syntax(const dicom *d);
int dicom_explicit(const dicom *d);
/* Nodes in the tree, elements and items (meta elements too), for tests. */
int dicom_nodes(const dicom *d);

/* The tree: DICOM_ROOT holds the top-level elements; a sequence read into
 * holds its items (tag DICOM_ITEM); an item holds its elements.  -1: none. */
int dicom_first(const dicom *d, int node);
int dicom_next(const dicom *d, int node);
int dicom_child(const dicom *d, int node, uint32_t tag);   /* first child with tag */
uint32_t dicom_tag(const dicom *d, int node);
size_t dicom_offset(const dicom *d, int node);             /* of its tag in buf */
int dicom_is_sequence(const dicom *d, int node);           /* read into: has items */
/* An element's value bytes (NULL and 0 for a sequence read into or an
 * element of undefined length), and their offset in buf. */
const unsigned char *dicom_value(const dicom *d, int node, size_t *len);
size_t dicom_value_offset(const dicom *d, int node);

#endif
