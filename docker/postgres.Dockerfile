# PostgreSQL 15 from Debian 12's own package (postgresql-15, as the tests run it) for the compose
# file's `replicas` profile, on the same base image as soiqd (docker/make-base-image), so nothing
# comes from Docker Hub. The official image's variables: POSTGRES_USER (default postgres),
# POSTGRES_DB (default: the user's name), POSTGRES_PASSWORD (required on the first start); the
# cluster is made in the volume /var/lib/postgresql/data on the first start
# (docker/postgres-entrypoint) and listens on every address of the container, password required.
#   podman build -f docker/postgres.Dockerfile -t soiq-postgres:15 .
ARG BASE=localhost/debian:12
FROM ${BASE}
# No "main" cluster made by the package: the entrypoint makes the one cluster, in the volume.
RUN mkdir -p /etc/postgresql-common/createcluster.d \
 && echo 'create_main_cluster = false' >/etc/postgresql-common/createcluster.d/soiq.conf \
 && apt-get update -qq \
 && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends postgresql-15 \
 && rm -rf /var/lib/apt/lists/* \
 && mkdir -p /var/lib/postgresql/data /var/run/postgresql \
 && chown postgres:postgres /var/lib/postgresql/data /var/run/postgresql \
 && chmod 700 /var/lib/postgresql/data
COPY docker/postgres-entrypoint /usr/local/bin/postgres-entrypoint
ENV PATH=/usr/lib/postgresql/15/bin:$PATH \
    PGDATA=/var/lib/postgresql/data
USER postgres
VOLUME /var/lib/postgresql/data
EXPOSE 5432
HEALTHCHECK --interval=5s --timeout=5s --retries=10 CMD ["pg_isready", "-h", "127.0.0.1", "-q"]
# SIGINT: PostgreSQL's fast shutdown (open sessions are ended, the checkpoint is written).
STOPSIGNAL SIGINT
ENTRYPOINT ["postgres-entrypoint"]
