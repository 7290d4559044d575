"""One router per resource (prefix + tag); operation ids are ``<tag>-<route name>``."""
