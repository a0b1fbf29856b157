/* dlist.h -- unlinking an element from an intrusive doubly linked list,
 * one whose elements carry prev and next pointers.
 *
 * DLIST_APPEND(head, tail, x): x joins the list whose first and last
 * elements the lvalues head and tail hold, at its end.
 * DLIST_UNLINK(head, tail, x): x leaves that list; x's own pointers are
 * left as they were.  DLIST_UNLINK_HEAD(head, x): the same for a list that
 * keeps no last element. */
#ifndef DLIST_H
#define DLIST_H

#define DLIST_APPEND(head, tail, x)                                            \
  do {                                                                         \
    (x)->next = NULL;                                                          \
    (x)->prev = (tail);                                                        \
    if (tail)                                                                  \
      (tail)->next = (x);                                                      \
    else                                                                       \
      (head) = (x);                                                            \
    (tail) = (x);                                                              \
  } while (0)

#define DLIST_UNLINK_HEAD(head, x)                                             \
  do {                                                                         \
    if ((x)->prev)                                                             \
      (x)->prev->next = (x)->next;                                             \
    else                                                                       \
      (head) = (x)->next;                                                      \
    if ((x)->next) (x)->next->prev = (x)->prev;                                \
  } while (0)

#define DLIST_UNLINK(head, tail, x)                                            \
  do {                                                                         \
    if ((x)->prev)                                                             \
      (x)->prev->next = (x)->next;                                             \
    else                                                                       \
      (head) = (x)->next;                                                      \
    if ((x)->next)                                                             \
      (x)->next->prev = (x)->prev;                                             \
    else                                                                       \
      (tail) = (x)->prev;                                                      \
  } while (0)

#endif
