// A localhost static file server for the web test and the demo, with single-range
// HTTP Range support (python3 -m http.server has none, and the plugin's range
// streaming should be tested against a server that honours them). It keeps a log
// of what it answered so the test can check which requests were ranged.
//   node tests/web/static_server.mjs [ROOT] [PORT]     (default: repository root, 8000)
import http from 'node:http';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const TYPES = {
	'.html': 'text/html; charset=utf-8', '.js': 'text/javascript', '.mjs': 'text/javascript',
	'.json': 'application/json', '.wasm': 'application/wasm', '.glb': 'model/gltf-binary',
	'.gltf': 'model/gltf+json', '.bin': 'application/octet-stream', '.css': 'text/css', '.png': 'image/png',
};

// Starts serving `root` on 127.0.0.1:`port` (0: any free port). Resolves to
// { server, url, log } where log lists { path, status, range }.
export function startStaticServer( root, port = 0 ) {

	const log = [];
	const server = http.createServer( ( req, res ) => serve( root, req, res, log ) );
	return new Promise( ( resolve, reject ) => {

		server.once( 'error', reject );
		server.listen( port, '127.0.0.1', () => {

			resolve( { server, url: `http://127.0.0.1:${server.address().port}`, log } );

		} );

	} );

}

function serve( root, req, res, log ) {

	const urlPath = decodeURIComponent( new URL( req.url, 'http://x' ).pathname );
	const file = withIndex( path.resolve( root, '.' + urlPath ) );
	const stat = file.startsWith( path.resolve( root ) ) && fs.existsSync( file ) ? fs.statSync( file ) : null;
	if ( ! stat || ! stat.isFile() ) return answer( res, log, urlPath, 404, null );
	const headers = { 'Content-Type': TYPES[ path.extname( file ) ] || 'application/octet-stream', 'Accept-Ranges': 'bytes' };
	const range = parseRange( req.headers.range, stat.size );
	if ( range === 'invalid' ) return answer( res, log, urlPath, 416, { 'Content-Range': `bytes */${stat.size}` } );
	if ( range ) headers[ 'Content-Range' ] = `bytes ${range.start}-${range.end}/${stat.size}`;
	const { start, end } = range || { start: 0, end: stat.size - 1 };
	headers[ 'Content-Length' ] = String( Math.max( 0, end - start + 1 ) );
	log.push( { path: urlPath, status: range ? 206 : 200, range: req.headers.range || null } );
	res.writeHead( range ? 206 : 200, headers );
	if ( req.method === 'HEAD' || end < start ) return res.end();
	fs.createReadStream( file, { start, end } ).pipe( res );

}

function withIndex( file ) {

	return fs.existsSync( file ) && fs.statSync( file ).isDirectory() ? path.join( file, 'index.html' ) : file;

}

function answer( res, log, urlPath, status, headers ) {

	log.push( { path: urlPath, status, range: null } );
	res.writeHead( status, headers || {} );
	res.end();

}

// One "bytes=a-b" / "bytes=a-" / "bytes=-n" range; anything else is served whole.
function parseRange( header, size ) {

	const match = /^bytes=(\d*)-(\d*)$/.exec( header || '' );
	if ( ! match || ( match[ 1 ] === '' && match[ 2 ] === '' ) ) return null;
	let start = match[ 1 ] === '' ? size - Number( match[ 2 ] ) : Number( match[ 1 ] );
	let end = match[ 1 ] === '' || match[ 2 ] === '' ? size - 1 : Number( match[ 2 ] );
	start = Math.max( 0, start );
	end = Math.min( end, size - 1 );
	return start <= end ? { start, end } : 'invalid';

}

if ( process.argv[ 1 ] === fileURLToPath( import.meta.url ) ) {

	const root = process.argv[ 2 ] || path.resolve( path.dirname( fileURLToPath( import.meta.url ) ), '../..' );
	const { url } = await startStaticServer( root, Number( process.argv[ 3 ] || 8000 ) );
	console.log( `serving ${root} at ${url}/ (demo: ${url}/samples/web/)` );

}
