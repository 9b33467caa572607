"""Tools for a course: assignment variants per student (:mod:`~mechanisms.course.assign`) and grading
(:mod:`~mechanisms.course.grading`)."""
